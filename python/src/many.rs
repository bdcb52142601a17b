//! `inrs.classify_many(domains, points)`: many domains at once, spread over the cores by the
//! library's `locate_many` / `locate_each` (each domain through the one decision of
//! `Containment`, as `Domain.classify` takes it), the GIL released.

use numpy::{IntoPyArray, PyArray1, PyReadonlyArray2};
use pyo3::prelude::*;

use inrs::{Domain, Location, Point};

use crate::domain::{NativeDomain, contain_options};
use crate::errors::value_error;
use crate::points::{pairs, with_point_source};
use crate::threads::with_threads;

/// One domain's codes (0 outside, 1 inside, 2 boundary), or why it could not be prepared.
type Answer = Result<Vec<i8>, String>;

/// The codes of the points in every domain: with `shared` (an `(N, 2)` float64 array, any
/// layout, read in place) every domain classifies the same points; with `each` (one such
/// array per domain) each domain its own. Returns, per domain in order, its int8 codes or
/// `None`, and its error message or `None`: the Python layer raises or keeps them.
#[pyfunction]
#[pyo3(signature = (domains, shared, each, method, tol, fill_rule, threads))]
#[allow(clippy::too_many_arguments, clippy::type_complexity)]
pub(crate) fn classify_many<'py>(
    py: Python<'py>,
    domains: Vec<Bound<'py, NativeDomain>>,
    shared: Option<PyReadonlyArray2<'py, f64>>,
    each: Option<Vec<PyReadonlyArray2<'py, f64>>>,
    method: &str,
    tol: f64,
    fill_rule: &str,
    threads: usize,
) -> PyResult<(Vec<Option<Bound<'py, PyArray1<i8>>>>, Vec<Option<String>>)> {
    let options = contain_options(tol, method, fill_rule)?;
    let refs: Vec<&Domain> = domains.iter().map(|d| &d.get().domain).collect();
    let answers: Vec<Answer> = match (&shared, &each) {
        (Some(xy), None) => {
            let pts = pairs(xy)?;
            py.detach(|| {
                with_threads(threads, || {
                    with_point_source!(pts, |points| inrs::locate_many(&refs, &points, options))
                })
            })?
            .into_iter()
            .map(codes)
            .collect()
        }
        (None, Some(arrays)) => {
            if arrays.len() != refs.len() {
                return Err(value_error(format!(
                    "{} domains but {} point arrays: give one array per domain",
                    refs.len(),
                    arrays.len()
                )));
            }
            let mut views = Vec::with_capacity(arrays.len());
            for (k, a) in arrays.iter().enumerate() {
                views.push(pairs(a).map_err(|e| value_error(format!("points[{k}]: {e}")))?);
            }
            py.detach(|| {
                with_threads(threads, || {
                    // One copy of each array as points (cheap beside a domain's build), so
                    // that every batch has the one point type `locate_each` takes.
                    let copies: Vec<Vec<Point>> = views.iter().map(|v| v.to_vec()).collect();
                    let batches: Vec<(&Domain, &Vec<Point>)> =
                        refs.iter().copied().zip(copies.iter()).collect();
                    inrs::locate_each(&batches, options)
                })
            })?
            .into_iter()
            .map(codes)
            .collect()
        }
        _ => {
            return Err(value_error(
                "give either shared points or one array per domain",
            ));
        }
    };
    let mut arrays = Vec::with_capacity(answers.len());
    let mut errors = Vec::with_capacity(answers.len());
    for a in answers {
        match a {
            Ok(c) => {
                arrays.push(Some(c.into_pyarray(py)));
                errors.push(None);
            }
            Err(e) => {
                arrays.push(None);
                errors.push(Some(e));
            }
        }
    }
    Ok((arrays, errors))
}

/// A domain's locations as codes, or its error as a message.
fn codes(r: Result<Vec<Location>, inrs::ContainError>) -> Answer {
    r.map(|l| l.iter().map(|l| l.code()).collect())
        .map_err(|e| e.to_string())
}
