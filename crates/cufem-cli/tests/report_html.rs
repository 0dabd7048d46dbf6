//! `report.html` (issue 51), read as a file: self-contained (its scripts
//! inline, nothing fetched), bounded in size, its text unable to close the
//! script that holds it, its data those of the run (the charts the CSVs,
//! the 3D view the mesh and displacement of `result.vtu`), and
//! `output.report = false` writing none. What a browser draws from it is
//! tests/browser (`bash tests/browser/run_browser_test.sh`).

use std::path::{Path, PathBuf};
use std::process::Command;

use base64::Engine as _;
use serde_json::Value;

/// The Timoshenko cantilever (0.1 × 1 × 0.1 m) with `title` and `extra`
/// appended, run into a fresh folder; returns the folder.
fn run(name: &str, title: &str, extra: &str) -> PathBuf {
    let root = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
    let text = std::fs::read_to_string(root.join("examples/cantilever_timoshenko.toml")).unwrap();
    let text = text.replace("title = \"Cantilever, tip shear (Timoshenko check)\"", &format!("title = {title:?}"));
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let model = dir.join("model.toml");
    std::fs::write(&model, format!("{text}\n{extra}")).unwrap();
    let out = dir.join("out");
    let run = Command::new(env!("CARGO_BIN_EXE_cufem"))
        .args(["run", model.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"])
        .output()
        .unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    out
}

fn files(out: &Path) -> Vec<String> {
    let summary: Value = serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    summary["files"].as_array().unwrap().iter().map(|f| f.as_str().unwrap().to_string()).collect()
}

/// Little-endian `f32`s from base64.
fn f32s(b64: &str) -> Vec<f64> {
    let raw = base64::engine::general_purpose::STANDARD.decode(b64).unwrap();
    raw.chunks_exact(4).map(|b| f32::from_le_bytes(b.try_into().unwrap()) as f64).collect()
}

/// The largest |u| over result.vtu's points: its `displacement` array
/// (binary: a UInt64 byte count, then little-endian Float64, base64).
fn vtu_largest_displacement(out: &Path) -> f64 {
    let text = std::fs::read_to_string(out.join("result.vtu")).unwrap();
    let doc = roxmltree::Document::parse(&text).unwrap();
    let a = doc.descendants().find(|n| n.attribute("Name") == Some("displacement")).unwrap();
    let raw = base64::engine::general_purpose::STANDARD.decode(a.text().unwrap().trim()).unwrap();
    let values: Vec<f64> = raw[8..].chunks_exact(8).map(|b| f64::from_le_bytes(b.try_into().unwrap())).collect();
    values.chunks(3).map(|u| (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt()).fold(0.0, f64::max)
}

/// The page inlines every script (four libraries and the page's own, and
/// the data), links nothing over the network, stays small for a small
/// model, and a title that tries to close the data's script element stays
/// text: the page still has its five script elements and the title comes
/// back whole from the data. Its data are the run's: a chart per history
/// and line CSV with its rows, the cantilever's box [0, 0.1] × [0, 1] × [0, 0.1] m
/// (the model file), and the largest displacement on the surface equal to
/// result.vtu's largest (the tip's corner, on the surface) to f32 precision.
#[test]
fn the_page_is_self_contained_and_holds_the_run() {
    let title = "tip </script><script>alert(1)</script> <!-- & \"quoted\" ü";
    let out = run("report_html", title, "");
    assert!(files(&out).contains(&"report.html".to_string()), "summary.json lists report.html");
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    let size = html.len();
    // the libraries are ~690 kB; this model's data is small
    assert!(size < 1_500_000, "report.html of the small cantilever is {size} bytes");
    assert_eq!(html.matches("<script").count(), 5, "four inline scripts and the data");
    assert_eq!(html.matches("</script>").count(), 5, "a title cannot close a script element");
    for link in ["src=\"http", "src='http", "href=\"http", "href='http", "url(http", "<link", "<script src", "@import"]
    {
        assert!(!html.contains(link), "report.html holds {link:?}");
    }
    let start = html.find("id=\"cufem-data\">").unwrap() + "id=\"cufem-data\">".len();
    let end = start + html[start..].find("</script>").unwrap();
    let data: Value = serde_json::from_str(&html[start..end]).unwrap();
    assert_eq!(data["title"], title);

    // a chart per history and line CSV, with its rows as points
    let mut csvs: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|f| (f.starts_with("history") || f.starts_with("line_")) && f.ends_with(".csv"))
        .collect();
    csvs.sort();
    let charts = data["charts"].as_array().unwrap();
    let mut names: Vec<String> = charts.iter().map(|c| format!("{}.csv", c["name"].as_str().unwrap())).collect();
    names.sort();
    assert_eq!(names, csvs);
    for c in charts {
        let rows = std::fs::read_to_string(out.join(format!("{}.csv", c["name"].as_str().unwrap()))).unwrap();
        let rows = rows.lines().count() - 1;
        let data = c["data"].as_array().unwrap();
        assert_eq!(data.len(), c["series"].as_array().unwrap().len() + 1);
        assert!(data.iter().all(|d| d.as_array().unwrap().len() == rows), "{} has {rows} rows", c["name"]);
    }

    let view = &data["view"];
    let bbox: Vec<f64> = view["bbox"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
    for (got, want) in bbox.iter().zip([0.0, 0.0, 0.0, 0.1, 1.0, 0.1]) {
        assert!((got - want).abs() < 1e-12, "box {bbox:?}");
    }
    let frames = view["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 1, "one step: the end only");
    let u = f32s(frames[0]["displacement"].as_str().unwrap());
    let n = view["vertices"].as_u64().unwrap() as usize;
    assert_eq!(u.len(), 3 * n);
    let largest = u.chunks(3).map(|u| (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt()).fold(0.0, f64::max);
    let vtu = vtu_largest_displacement(&out);
    assert!((largest - vtu).abs() <= 1e-6 * vtu, "largest |u| {largest} on the page, {vtu} in result.vtu");
}

/// `output.report = false` writes no report.html and lists none.
#[test]
fn output_report_false_writes_no_page() {
    let out = run("report_html_off", "off", "[output]\nreport = false\n");
    assert!(!out.join("report.html").exists());
    assert!(!files(&out).iter().any(|f| f == "report.html"));
    assert!(out.join("result.vtu").exists());
}
