//! The command-line cells of docs/FRONTENDS.md not exercised elsewhere: `classify` by every
//! `--method` and `--fill-rule` against analytic locations, and `mesh --refine`.

mod common;
use common::{fixture, inrs, inrs_ok, last_column, temp_file};

#[test]
fn classify_by_every_method_and_fill_rule() {
    // Two counter-clockwise circles about the origin, radii 2 and 1: winding number 2 at the
    // centre, 1 in the ring.
    let domain = temp_file(
        "nested.json",
        r#"{"curves": [{"circle": {"center": [0, 0], "radius": 2}},
                       {"circle": {"center": [0, 0], "radius": 1}}]}"#,
    );
    let points = temp_file("probes.csv", "x,y\n0,0\n1.5,0\n3,0\n0,1\n");
    let even_odd = ["outside", "inside", "outside", "boundary"];
    for method in ["fast", "inrs1", "inrs2", "gwn"] {
        for rule in ["even-odd", "nonzero"] {
            let text = inrs_ok(&[
                "classify",
                "--domain",
                &domain,
                "--points",
                &points,
                "--method",
                method,
                "--fill-rule",
                rule,
            ]);
            // Every method honours the fill rule: nonzero fills the inner disc (winding 2).
            let want = if rule == "nonzero" {
                ["inside", "inside", "outside", "boundary"]
            } else {
                even_odd
            };
            assert_eq!(last_column(&text), want, "{method} {rule}");
        }
    }
}

#[test]
fn mesh_refine_splits_every_triangle() {
    let domain = fixture("inrs-paper/s4_disk_ellipse_segment.json");
    let triangles = |refine: &str| -> (usize, usize) {
        let text = inrs_ok(&["mesh", "--domain", &domain, "--ny", "8", "--refine", refine]);
        let m: serde_json::Value = serde_json::from_str(&text).unwrap();
        (
            m["triangles"].as_array().unwrap().len(),
            m["vertices"].as_array().unwrap().len(),
        )
    };
    let (t, v) = triangles("none");
    assert!(t > 10);
    // Clough–Tocher adds one vertex per triangle and splits it in 3; Powell–Sabin splits it in 6.
    assert_eq!(triangles("ct"), (3 * t, v + t));
    assert_eq!(triangles("ps").0, 6 * t);
    let plain = inrs_ok(&["mesh", "--domain", &domain, "--ny", "8"]);
    assert_eq!(
        serde_json::from_str::<serde_json::Value>(&plain).unwrap()["triangles"]
            .as_array()
            .unwrap()
            .len(),
        t
    );
}

/// `inrs info` on a part lists its solids with their shells, then its faces (a whole sphere on
/// its natural bounds); `part.step#solid:K` lists that solid and its faces.
#[test]
fn cad_solids_and_shells_are_listed() {
    let part = fixture("cad/box_void.step");
    let listing = inrs_ok(&["info", "--domain", &part]);
    assert!(
        listing.contains("1 STEP solid, 2 shells, 7 faces (7 read, 0 refused); tolerance 1e-7"),
        "{listing}"
    );
    assert!(
        listing.contains("solid 0   #15       2 shells"),
        "{listing}"
    );
    assert!(
        listing.contains("outer shell 0   #16       closed 6 faces 0-5"),
        "{listing}"
    );
    assert!(
        listing.contains("void  shell 1   #346      closed 1 face 6"),
        "{listing}"
    );
    assert!(
        listing.contains("SPHERICAL_SURFACE") && listing.contains("natural bounds"),
        "{listing}"
    );
    let solid = inrs_ok(&["info", "--domain", &format!("{part}#solid:0")]);
    assert_eq!(
        solid.lines().filter(|l| l.starts_with("face ")).count(),
        7,
        "{solid}"
    );
    assert!(solid.contains("solid 0"), "{solid}");
}

/// `--domain part.step#face:K` reads face K in its (u, v) for every command; `inrs info` on the
/// file lists its faces.
#[test]
fn cad_faces_are_listed_and_classified() {
    let plate = fixture("cad/plate.step");
    let listing = inrs_ok(&["info", "--domain", &plate]);
    assert!(
        listing.contains("0 STEP solids, 1 shell, 1 face (1 read, 0 refused); tolerance 1e-7"),
        "{listing}"
    );
    assert!(listing.contains("face 0    #99       PLANE"), "{listing}");
    assert!(listing.contains("loops 2  curves 5"), "{listing}");
    let points = temp_file("plate_uv.csv", "x,y\n1,1\n5,5\n11,5\n7,5\n");
    let spec = format!("{plate}#face:0");
    let out = inrs_ok(&["classify", "--domain", &spec, "--points", &points]);
    assert_eq!(
        last_column(&out),
        ["inside", "outside", "outside", "boundary"]
    );
    let out = inrs(&[
        "classify",
        "--domain",
        &format!("{plate}#face:1"),
        "--points",
        &points,
    ]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("face 1 does not exist: the file has 1 face"),
        "{err}"
    );
}
