//! The STEP reader: small hand-written files with analytic answers, the real files of
//! `FreeCAD`'s `Idflibs` and the gmsh demos (invariants and face counts; skipped with a
//! message when absent, failing under `INRS_REQUIRE_SYSTEM_FILES=1`), and hostile inputs
//! (each an `Err` with a one-line message, never a panic).

use rs_io::cad::CadModel;
use rs_io::cad::step::{gap_tolerance, read_step};
use rs_spline::prelude::*;
use rs_spline::{NurbsCurve, Point};

const IDF: &str = "/usr/share/freecad/Mod/Idf/Idflibs";
const GMSH: &str = "/usr/share/doc/gmsh-doc/doc/gmsh";

/// The largest gap between consecutive curves of the loops of a model's readable faces.
fn max_gap(m: &CadModel) -> f64 {
    let mut worst: f64 = 0.0;
    for f in &m.faces {
        if let Ok(loops) = &f.loops {
            for l in loops {
                for (i, c) in l.iter().enumerate() {
                    let next = &l[(i + 1) % l.len()];
                    worst = worst.max(c.end_point().distance(next.start_point()));
                }
            }
        }
    }
    worst
}

/// The signed area of a closed loop (sum of the curves' area integrals).
fn loop_area(l: &[NurbsCurve]) -> f64 {
    l.iter().map(|c| c.area_integral().value).sum()
}

// ---------------------------------------------------------------------------------------
// Real files

/// The expected face counts (OpenCASCADE 7.8's face explorer on the same files).
const IDF_FACES: [(&str, usize); 28] = [
    ("0603_SMD.stp", 90),
    ("0805_SMD.stp", 90),
    ("1206_SMD.stp", 94),
    ("1210_SMD.stp", 16),
    ("1812_SMD.stp", 91),
    ("2225_SMD.stp", 52),
    ("2512_SMD.stp", 95),
    ("CAP_50SGV_8_10.stp", 48),
    ("EPL22_6_16.stp", 36),
    ("I22_2_5_16.stp", 36),
    ("I22_2_5_16withEPL22_6_16.stp", 72),
    ("MSOP_10.stp", 157),
    ("RLF_12545.stp", 47),
    ("RLF_7030.stp", 72),
    ("SMB_DO_214AA.stp", 44),
    ("SMC_DO_214AB.stp", 44),
    ("SOD_323.stp", 75),
    ("SOD_523.stp", 32),
    ("SOT23.stp", 73),
    ("SOT404.stp", 75),
    ("SOT428_DPAK.stp", 49),
    ("SOT_323_3.stp", 45),
    ("SOT_96.stp", 141),
    ("TCMT1107_4.stp", 70),
    ("TSM_103_01_L_DV_A.stp", 434),
    ("TSM_104_01_L_DV_A.stp", 552),
    ("TSS0P_8.stp", 129),
    ("VC0603_SMD.stp", 90),
];

/// Checks the invariants of a real file's model; returns (read, refused).
fn check_real(name: &str, m: &CadModel) -> (usize, usize) {
    let tol = gap_tolerance(m.tolerance);
    let (mut ok, mut refused) = (0, 0);
    for (k, f) in m.faces.iter().enumerate() {
        match &f.loops {
            Ok(loops) => {
                ok += 1;
                assert!(!loops.is_empty(), "{name} face {k} {}", f.entity);
                for l in loops {
                    for (i, c) in l.iter().enumerate() {
                        let next = &l[(i + 1) % l.len()];
                        let gap = c.end_point().distance(next.start_point());
                        assert!(
                            gap <= tol,
                            "{name} face {k} {}: gap {gap:e} > {tol:e}",
                            f.entity
                        );
                    }
                }
                let outer = loop_area(&loops[0]);
                assert!(outer.abs() > 0.0, "{name} face {k} {}: zero area", f.entity);
            }
            Err(e) => {
                refused += 1;
                assert!(!e.contains('\n'), "{name}: {e}");
                eprintln!("{name} face {k} {} ({}): {e}", f.entity, f.surface);
            }
        }
    }
    (ok, refused)
}

#[test]
fn idflibs_every_face_reads_and_every_loop_closes() {
    let mut total = (0, 0);
    for (file, faces) in IDF_FACES {
        let path = format!("{IDF}/{file}");
        let Some(text) = rs_testkit::system_file(&path, "freecad") else {
            return;
        };
        let m = read_step(&text).unwrap_or_else(|e| panic!("{file}: {e}"));
        assert_eq!(m.faces.len(), faces, "{file}");
        assert!(m.tolerance.is_some(), "{file}");
        let (ok, refused) = check_real(file, &m);
        eprintln!(
            "{file}: {ok} read, {refused} refused, max gap {:e}",
            max_gap(&m)
        );
        total.0 += ok;
        total.1 += refused;
    }
    eprintln!("Idflibs: {} faces read, {} refused", total.0, total.1);
    assert_eq!(total.1, 0, "every Idflibs face has pcurves and must read");
}
