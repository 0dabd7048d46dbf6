//! Division of an interval into elements: uniform, piecewise uniform with
//! optional geometric grading, or explicit element boundaries ("node lines").

use super::MeshError;

/// One graded segment of a [`Division`].
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Segment {
    /// Start coordinate (m).
    pub from: f64,
    /// End coordinate (m).
    pub to: f64,
    /// Number of elements in the segment (≥ 1).
    pub elements: usize,
    /// Ratio last element length / first element length (1 = uniform).
    pub ratio: f64,
}

/// How an interval is cut into elements. The result is always the sorted
/// list of element boundaries (`elements + 1` coordinates).
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Division {
    /// Explicit, strictly increasing element boundaries.
    Lines(Vec<f64>),
    /// Consecutive segments, each uniform or geometrically graded.
    Segments(Vec<Segment>),
}

impl Division {
    /// Uniform division of `[from, to]` into `elements` elements.
    #[cfg(test)]
    pub(crate) fn uniform(from: f64, to: f64, elements: usize) -> Self {
        Self::Segments(vec![Segment { from, to, elements, ratio: 1.0 }])
    }

    /// The element boundaries. `key` names the model-file key in errors.
    pub fn lines(&self, key: &str) -> Result<Vec<f64>, MeshError> {
        let lines = match self {
            Self::Lines(l) => l.clone(),
            Self::Segments(segs) => {
                let mut out: Vec<f64> = Vec::new();
                for (k, s) in segs.iter().enumerate() {
                    let skey = format!("{key}.segments[{k}]");
                    if s.elements == 0 {
                        return Err(MeshError::invalid(format!("{skey}.elements"), "0", "an integer ≥ 1"));
                    }
                    let (lo, hi) = super::GRADING_RATIO;
                    if !(s.ratio >= lo && s.ratio <= hi) {
                        return Err(MeshError::invalid(
                            format!("{skey}.ratio"),
                            crate::numbers::number(s.ratio),
                            format!("a number from {lo:e} to {hi:e} (last/first element length)"),
                        ));
                    }
                    if let Some(&last) = out.last()
                        && (last - s.from).abs() > 1e-12 * (1.0 + last.abs())
                    {
                        return Err(MeshError::invalid(
                            format!("{skey}.from"),
                            s.from.to_string(),
                            format!("the end of the previous segment ({last})"),
                        ));
                    }
                    let n = s.elements;
                    // geometric progression with q^(n-1) = ratio
                    let q = if n > 1 { s.ratio.powf(1.0 / (n as f64 - 1.0)) } else { 1.0 };
                    let weights: Vec<f64> = (0..n).map(|i| q.powi(i as i32)).collect();
                    let total: f64 = weights.iter().sum();
                    if out.is_empty() {
                        out.push(s.from);
                    }
                    let mut acc = 0.0;
                    for (i, w) in weights.iter().enumerate() {
                        acc += w;
                        out.push(if i + 1 == n { s.to } else { s.from + (s.to - s.from) * acc / total });
                    }
                }
                out
            }
        };
        if lines.len() < 2 {
            return Err(MeshError::invalid(key.to_string(), format!("{lines:?}"), "at least two element boundaries"));
        }
        let shown = || {
            if lines.len() <= 8 {
                format!("{lines:?}")
            } else {
                format!("{} values from {} to {}", lines.len(), lines[0], lines[lines.len() - 1])
            }
        };
        for w in lines.windows(2) {
            if !(w[1] > w[0]) || !w[0].is_finite() || !w[1].is_finite() {
                return Err(MeshError::invalid(key.to_string(), shown(), "strictly increasing finite coordinates"));
            }
        }
        let (first, last) = (lines[0], lines[lines.len() - 1]);
        if first.abs().max(last.abs()) > super::MAX_COORD {
            return Err(MeshError::invalid(
                key.to_string(),
                shown(),
                format!(
                    "coordinates within ±{:e} m (a structure larger than 10 km is not plausible)",
                    super::MAX_COORD
                ),
            ));
        }
        let span = last - first;
        if let Some(w) = lines.windows(2).find(|w| w[1] - w[0] < super::MIN_RELATIVE_SIZE * span) {
            return Err(MeshError::invalid(
                key.to_string(),
                shown(),
                format!(
                    "elements of at least {:e} of the divided span (the element from {} to {} is shorter)",
                    super::MIN_RELATIVE_SIZE,
                    w[0],
                    w[1]
                ),
            ));
        }
        Ok(lines)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uniform_and_graded_segments() {
        let d = Division::uniform(0.0, 1.0, 4);
        assert_eq!(d.lines("x").unwrap(), vec![0.0, 0.25, 0.5, 0.75, 1.0]);
        let d = Division::Segments(vec![
            Segment { from: 0.0, to: 0.2, elements: 2, ratio: 1.0 },
            Segment { from: 0.2, to: 0.5, elements: 3, ratio: 4.0 },
        ]);
        let l = d.lines("x").unwrap();
        assert_eq!(l.len(), 6);
        assert!((l[2] - 0.2).abs() < 1e-15 && (l[5] - 0.5).abs() < 1e-15);
        // ratio 4 over 3 elements: lengths h, 2h, 4h with 7h = 0.3
        assert!(((l[3] - l[2]) - 0.3 / 7.0).abs() < 1e-14);
        assert!(((l[5] - l[4]) - 4.0 * 0.3 / 7.0).abs() < 1e-14);
    }

    #[test]
    fn rejects_non_increasing_lines() {
        let err = Division::Lines(vec![0.0, 0.3, 0.2]).lines("bodies[0].section.x").unwrap_err();
        assert!(err.to_string().contains("bodies[0].section.x"));
    }
}
