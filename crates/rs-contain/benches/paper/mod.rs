//! The paper's three domains as the benchmarks measure them: each with `n` Halton points of
//! its reference box, the inside count its fixture file records for them, and its classifier.

// Each benchmark target compiles this module and reads only the fields it measures.
#![allow(dead_code)]

use rs_contain::baselines::halton_points;
use rs_contain::{Classifier, ContainOptions};
use rs_spline::{Domain, Point};

/// One of the paper's domains, ready to be measured.
pub(crate) struct PaperCase {
    /// The fixture's name.
    pub(crate) name: &'static str,
    /// The domain.
    pub(crate) domain: Domain,
    /// Halton points of the reference box.
    pub(crate) points: Vec<Point>,
    /// How many of `points` are inside (the fixture's reference count).
    pub(crate) inside: usize,
    /// The domain's classifier with the default options.
    pub(crate) classifier: Classifier,
}

/// The paper's domains with `n` points each (`n` must be a count the fixtures record).
pub(crate) fn paper_cases(n: usize) -> impl Iterator<Item = PaperCase> {
    rs_testkit::PAPER_DOMAINS.into_iter().map(move |name| {
        let meta = rs_testkit::inrs_fixture(name);
        let inside = meta.inside_count(n).expect("reference count");
        let points = halton_points(n, meta.reference_box.expect("reference box"));
        let classifier = Classifier::new(&meta.domain, ContainOptions::default()).expect("closed");
        PaperCase {
            name,
            domain: meta.domain,
            points,
            inside,
            classifier,
        }
    })
}
