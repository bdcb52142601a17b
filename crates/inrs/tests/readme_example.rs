//! The library example of README.md ("Using the library"), kept compiling and true.

use inrs::contain::Locate;
use inrs::{Classifier, ContainOptions, Location, Method};

#[test]
fn readme_library_example() -> Result<(), Box<dyn std::error::Error>> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../fixtures/inrs-paper/s5_lune.json"
    );
    let domain = inrs::io::json::domain_from_json_file(path)?;
    let classifier = Classifier::new(&domain, ContainOptions::default())?;
    let points = vec![inrs::Point::new(0.1, 0.2)];
    let a = classifier.locate_all(&points);
    let b = classifier.locate_all_with(Method::InRS2, &points);
    let locator = classifier.locator();
    let c = locator.locate_all_parallel(&points);
    let d: Vec<Location> = locator.locate_iter(points.iter().copied()).collect();
    assert!(a == b && b == c && c == d);
    Ok(())
}
