//! The model as Python objects and back: TOML text ⇄ nested dicts, lists and
//! scalars (`cufem.Model.to_dict`, `cufem.Model.from_dict`), every value
//! that is not TOML refused by its key.

use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

use crate::ModelError;
use cufem::setup::ModelError as RustModelError;

/// TOML text → nested dicts and lists (a TOML syntax error is a `ModelError`
/// with the parser's message, as `cufem run` prints it).
#[pyfunction]
pub(crate) fn toml_to_object(py: Python<'_>, text: &str) -> PyResult<PyObject> {
    let value: toml::Table =
        toml::from_str(text).map_err(|e| ModelError::new_err(RustModelError::Parse(e.to_string()).to_string()))?;
    value_to_py(py, &toml::Value::Table(value))
}

/// Nested dicts and lists → TOML text (numpy scalars and arrays accepted;
/// `None` refused: TOML has no null).
#[pyfunction]
pub(crate) fn object_to_toml(obj: &Bound<'_, PyAny>) -> PyResult<String> {
    let value = py_to_value(obj, "")?;
    let toml::Value::Table(table) = value else {
        return Err(ModelError::new_err("model: expected a dict of model-file keys (a TOML table)"));
    };
    toml::to_string(&table).map_err(|e| ModelError::new_err(format!("model: cannot write as TOML: {e}")))
}

fn value_to_py(py: Python<'_>, v: &toml::Value) -> PyResult<PyObject> {
    Ok(match v {
        toml::Value::String(s) => s.into_pyobject(py)?.into_any().unbind(),
        toml::Value::Integer(i) => i.into_pyobject(py)?.into_any().unbind(),
        toml::Value::Float(f) => f.into_pyobject(py)?.into_any().unbind(),
        toml::Value::Boolean(b) => PyBool::new(py, *b).to_owned().into_any().unbind(),
        toml::Value::Datetime(d) => d.to_string().into_pyobject(py)?.into_any().unbind(),
        toml::Value::Array(a) => {
            let items = a.iter().map(|x| value_to_py(py, x)).collect::<PyResult<Vec<_>>>()?;
            PyList::new(py, items)?.into_any().unbind()
        }
        toml::Value::Table(t) => {
            let d = PyDict::new(py);
            for (k, x) in t {
                d.set_item(k, value_to_py(py, x)?)?;
            }
            d.into_any().unbind()
        }
    })
}

fn child(key: &str, name: impl std::fmt::Display) -> String {
    if key.is_empty() { name.to_string() } else { format!("{key}.{name}") }
}

fn py_to_value(obj: &Bound<'_, PyAny>, key: &str) -> PyResult<toml::Value> {
    let shown = || if key.is_empty() { "model".to_string() } else { key.to_string() };
    if obj.is_none() {
        return Err(ModelError::new_err(format!(
            "{} = None: expected a value (TOML has no null: leave the key out for its default)",
            shown()
        )));
    }
    if let Ok(b) = obj.downcast::<PyBool>() {
        return Ok(toml::Value::Boolean(b.is_true()));
    }
    if obj.is_instance_of::<PyInt>() {
        let i: i64 = obj
            .extract()
            .map_err(|_| ModelError::new_err(format!("{} = {}: expected an integer within ±9.2e18", shown(), obj)))?;
        return Ok(toml::Value::Integer(i));
    }
    if obj.is_instance_of::<PyFloat>() {
        return Ok(toml::Value::Float(obj.extract()?));
    }
    if let Ok(s) = obj.downcast::<PyString>() {
        return Ok(toml::Value::String(s.extract::<String>()?));
    }
    if let Ok(d) = obj.downcast::<PyDict>() {
        let mut t = toml::Table::new();
        for (k, v) in d.iter() {
            let Ok(k) = k.downcast::<PyString>() else {
                return Err(ModelError::new_err(format!(
                    "{} has the key {}: expected string keys (model-file names)",
                    shown(),
                    k.repr()?
                )));
            };
            let k = k.extract::<String>()?;
            let v = py_to_value(&v, &child(key, &k))?;
            t.insert(k, v);
        }
        return Ok(toml::Value::Table(t));
    }
    if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        let mut a = Vec::new();
        for (i, v) in obj.try_iter()?.enumerate() {
            a.push(py_to_value(&v?, &child(key, i))?);
        }
        return Ok(toml::Value::Array(a));
    }
    // numpy scalars and arrays
    if obj.hasattr("tolist")? {
        return py_to_value(&obj.call_method0("tolist")?, key);
    }
    Err(ModelError::new_err(format!(
        "{} = {}: expected a number, string, bool, list or dict (type {})",
        shown(),
        obj.repr()?,
        obj.get_type().name()?
    )))
}
