//! Candidate points strictly inside the domain: Halton points in the bounding box kept when
//! the grid locator says [`Location::Inside`] (farther than the boundary tolerance from the
//! boundary).

use rs_contain::baselines::halton_points_from;
use rs_contain::{Classifier, Locate, Location};
use rs_spline::Point;

/// Most Halton points generated per candidate wanted: a domain that fills less than
/// `1 / 256` of its bounding box gets fewer candidates than wanted and an error, rather
/// than an unbounded search.
pub(crate) const MAX_GENERATED_PER_CANDIDATE: usize = 256;

/// The Halton points kept so far, and where the sequence continues: a retry adds to them.
#[derive(Debug)]
pub(crate) struct Candidates<'a> {
    classifier: &'a Classifier,
    points: Vec<Point>,
    /// Points of the sequence tried so far (the first, the box's corner, is skipped).
    generated: usize,
}

impl<'a> Candidates<'a> {
    pub(crate) fn new(classifier: &'a Classifier) -> Self {
        Self {
            classifier,
            points: Vec::new(),
            generated: 0,
        }
    }

    /// The points found inside.
    pub(crate) fn points(&self) -> &[Point] {
        &self.points
    }

    /// Points of the sequence tried.
    pub(crate) fn generated(&self) -> usize {
        self.generated
    }

    /// Tries further Halton points until `wanted` are inside or
    /// `MAX_GENERATED_PER_CANDIDATE * wanted` have been tried in all; keeps at most `wanted`.
    pub(crate) fn grow_to(&mut self, wanted: usize) {
        let bbox = self.classifier.boxes().bounding_box();
        let locator = self.classifier.locator();
        let budget = wanted.saturating_mul(MAX_GENERATED_PER_CANDIDATE);
        while self.points.len() < wanted && self.generated < budget {
            let missing = wanted - self.points.len();
            // Ask for the missing ones at the acceptance rate seen so far (at least 1 / 2).
            let rate = if self.generated > 0 {
                (self.points.len() as f64 / self.generated as f64).max(1.0 / 256.0)
            } else {
                0.5
            };
            let batch = ((missing as f64 / rate * 1.1) as usize + 64)
                .min(budget - self.generated)
                .max(1);
            let start = 1 + self.generated as u64;
            let points = halton_points_from(start, batch, bbox);
            let locations = locator.locate_all(&points);
            self.generated += batch;
            for (p, l) in points.into_iter().zip(locations) {
                if l == Location::Inside && self.points.len() < wanted {
                    self.points.push(p);
                }
            }
        }
    }
}
