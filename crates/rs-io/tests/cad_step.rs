//! The STEP reader: small hand-written files with analytic answers, the real files of
//! `FreeCAD`'s `Idflibs` and the gmsh demos (invariants and face counts; skipped with a
//! message when absent, failing under `INRS_REQUIRE_SYSTEM_FILES=1`), and hostile inputs
//! (each an `Err` with a one-line message, never a panic).

use rs_geom::brep::{Edge, Face, FaceError};
use rs_geom::surface::ParamSurface;
use rs_geom::{Point3, Surface};
use rs_io::cad::CadModel;
use rs_io::cad::step::{StepError, read_step};
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
// Hand-written files

/// A whole Part 21 file around `data`: one part whose shape is the surface model of the
/// shell `#100`, in millimetres and radians with an uncertainty of `1e-7`.
fn step_file(data: &str) -> String {
    format!(
        "ISO-10303-21;
HEADER;
FILE_DESCRIPTION((''),'2;1');
FILE_NAME('t.stp','2024-01-01T00:00:00',(''),(''),'','','');
FILE_SCHEMA(('AUTOMOTIVE_DESIGN {{ 1 0 10303 214 1 1 1 1 }}'));
ENDSEC;
DATA;
#9020=APPLICATION_CONTEXT('core data for automotive mechanical design processes');
#9021=PRODUCT_CONTEXT('',#9020,'mechanical');
#9022=PRODUCT('p','p','',(#9021));
#9023=PRODUCT_DEFINITION_FORMATION('','',#9022);
#9024=PRODUCT_DEFINITION_CONTEXT('part definition',#9020,'design');
#9001=PRODUCT_DEFINITION('design','',#9023,#9024);
#9004=PRODUCT_DEFINITION_SHAPE('','',#9001);
#9005=SHAPE_DEFINITION_REPRESENTATION(#9004,#9006);
#9006=MANIFOLD_SURFACE_SHAPE_REPRESENTATION('',(#9007),#9010);
#9007=SHELL_BASED_SURFACE_MODEL('',(#100));
#9010=(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#9014))GLOBAL_UNIT_ASSIGNED_CONTEXT((#9011,#9012,#9013))REPRESENTATION_CONTEXT('',''));
#9011=(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.));
#9012=(NAMED_UNIT(*)PLANE_ANGLE_UNIT()SI_UNIT($,.RADIAN.));
#9013=(NAMED_UNIT(*)SI_UNIT($,.STERADIAN.)SOLID_ANGLE_UNIT());
#9014=UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(1.E-07),#9011,'distance_accuracy_value','');
#9030=(GEOMETRIC_REPRESENTATION_CONTEXT(2)PARAMETRIC_REPRESENTATION_CONTEXT()REPRESENTATION_CONTEXT('2D',''));
{data}
ENDSEC;
END-ISO-10303-21;
"
    )
}

/// Builds instance text with running labels.
struct Builder {
    next: u64,
    text: String,
}

impl Builder {
    fn new() -> Self {
        Self {
            next: 200,
            text: String::new(),
        }
    }
    fn add(&mut self, body: &str) -> u64 {
        let id = self.next;
        self.next += 1;
        self.text += &format!("#{id}={body};\n");
        id
    }
    fn point(&mut self, p: &[f64]) -> u64 {
        let c: Vec<String> = p.iter().map(|x| format!("{x:?}")).collect();
        self.add(&format!("CARTESIAN_POINT('',({}))", c.join(",")))
    }
    fn dir(&mut self, d: &[f64]) -> u64 {
        let c: Vec<String> = d.iter().map(|x| format!("{x:?}")).collect();
        self.add(&format!("DIRECTION('',({}))", c.join(",")))
    }
    fn vertex(&mut self, p: [f64; 3]) -> u64 {
        let q = self.point(&p);
        self.add(&format!("VERTEX_POINT('',#{q})"))
    }
    /// A 3-D or 2-D line through `p` along `d` (magnitude 1).
    fn line(&mut self, p: &[f64], d: &[f64]) -> u64 {
        let (q, dd) = (self.point(p), self.dir(d));
        let v = self.add(&format!("VECTOR('',#{dd},1.)"));
        self.add(&format!("LINE('',#{q},#{v})"))
    }
    fn axis3(&mut self, o: [f64; 3], z: [f64; 3], x: [f64; 3]) -> u64 {
        let (p, a, r) = (self.point(&o), self.dir(&z), self.dir(&x));
        self.add(&format!("AXIS2_PLACEMENT_3D('',#{p},#{a},#{r})"))
    }
    fn axis2(&mut self, o: [f64; 2], x: [f64; 2]) -> u64 {
        let (p, r) = (self.point(&o), self.dir(&x));
        self.add(&format!("AXIS2_PLACEMENT_2D('',#{p},#{r})"))
    }
    /// A pcurve of `curve2d` on `surface`.
    fn pcurve(&mut self, surface: u64, curve2d: u64) -> u64 {
        let d = self.add(&format!(
            "DEFINITIONAL_REPRESENTATION('',(#{curve2d}),#9030)"
        ));
        self.add(&format!("PCURVE('',#{surface},#{d})"))
    }
    fn edge(&mut self, a: u64, b: u64, geometry: u64, same_sense: bool) -> u64 {
        self.add(&format!(
            "EDGE_CURVE('',#{a},#{b},#{geometry},{})",
            flag(same_sense)
        ))
    }
    fn oriented(&mut self, edge: u64, forward: bool) -> u64 {
        self.add(&format!("ORIENTED_EDGE('',*,*,#{edge},{})", flag(forward)))
    }
    fn bound(&mut self, edges: &[u64], outer: bool, forward: bool) -> u64 {
        let l = self.add(&format!("EDGE_LOOP('',({}))", refs(edges)));
        let kind = if outer {
            "FACE_OUTER_BOUND"
        } else {
            "FACE_BOUND"
        };
        self.add(&format!("{kind}('',#{l},{})", flag(forward)))
    }
    /// The face `#99` in the open shell `#100`, and the file.
    fn file(mut self, bounds: &[u64], surface: u64) -> String {
        self.text += &format!("#99=ADVANCED_FACE('',({}),#{surface},.T.);\n", refs(bounds));
        self.text += "#100=OPEN_SHELL('',(#99));\n";
        step_file(&self.text)
    }
}

fn flag(b: bool) -> &'static str {
    if b { ".T." } else { ".F." }
}

fn refs(ids: &[u64]) -> String {
    ids.iter()
        .map(|i| format!("#{i}"))
        .collect::<Vec<_>>()
        .join(",")
}

fn one_face(text: &str) -> Vec<Vec<NurbsCurve>> {
    let m = read_step(text.as_bytes()).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(m.faces.len(), 1);
    assert_eq!(m.tolerance.stated(), Some(1e-7));
    assert_eq!(m.faces[0].entity, "#99");
    m.faces[0].loops.clone().unwrap_or_else(|e| panic!("{e}"))
}

/// Asserts that consecutive curves of every loop meet (to `1e-12`) and returns the loops.
fn closed(loops: Vec<Vec<NurbsCurve>>) -> Vec<Vec<NurbsCurve>> {
    for l in &loops {
        for (i, c) in l.iter().enumerate() {
            let next = &l[(i + 1) % l.len()];
            let gap = c.end_point().distance(next.start_point());
            assert!(gap < 1e-12, "gap {gap:e} after curve {i}");
        }
    }
    loops
}

/// A point `(u, v)` of the plane of `plate`: `P + u x + v y`.
type PlaneFrame = ([f64; 3], [f64; 3], [f64; 3], [f64; 3]);

/// The plane z = 0 with its natural axes.
const FLAT: PlaneFrame = ([0.0; 3], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
/// A tilted plane through (1, 2, 3): axis (0, -0.6, 0.8), x (1, 0, 0), y = axis x x.
const TILTED: PlaneFrame = (
    [1.0, 2.0, 3.0],
    [0.0, -0.6, 0.8],
    [1.0, 0.0, 0.0],
    [0.0, 0.8, 0.6],
);

fn on_plane(f: &PlaneFrame, u: f64, v: f64) -> [f64; 3] {
    let (o, _, x, y) = f;
    [0, 1, 2].map(|i| o[i] + u * x[i] + v * y[i])
}

/// A 10 x 10 plate `[0, 10]^2` with a hole of radius 2 about (5, 5), in the plane `f`,
/// with or without pcurves.
fn plate(f: &PlaneFrame, pcurves: bool) -> String {
    let mut b = Builder::new();
    let ax = b.axis3(f.0, f.1, f.2);
    let plane = b.add(&format!("PLANE('',#{ax})"));
    let corners = [(0.0, 0.0), (10.0, 0.0), (10.0, 10.0), (0.0, 10.0)];
    let vs: Vec<u64> = corners
        .iter()
        .map(|&(u, v)| b.vertex(on_plane(f, u, v)))
        .collect();
    let mut outer = Vec::new();
    for i in 0..4 {
        let (p, q) = (corners[i], corners[(i + 1) % 4]);
        let d2 = [q.0 - p.0, q.1 - p.1].map(|x: f64| x / 10.0);
        let p3 = on_plane(f, p.0, p.1);
        let d3 = [0, 1, 2].map(|k| d2[0] * f.2[k] + d2[1] * f.3[k]);
        let l3 = b.line(&p3, &d3);
        let geometry = if pcurves {
            let l2 = b.line(&[p.0, p.1], &d2);
            let pc = b.pcurve(plane, l2);
            b.add(&format!("SURFACE_CURVE('',#{l3},(#{pc}),.PCURVE_S1.)"))
        } else {
            l3
        };
        let e = b.edge(vs[i], vs[(i + 1) % 4], geometry, true);
        outer.push(b.oriented(e, true));
    }
    // The hole: one closed circle edge from (7, 5), run clockwise in the plane (the inner
    // bound of a face runs so the face is on its left).
    let vh = b.vertex(on_plane(f, 7.0, 5.0));
    let cax = b.axis3(on_plane(f, 5.0, 5.0), f.1, f.2);
    let c3 = b.add(&format!("CIRCLE('',#{cax},2.)"));
    let geometry = if pcurves {
        let a2 = b.axis2([5.0, 5.0], [1.0, 0.0]);
        let c2 = b.add(&format!("CIRCLE('',#{a2},2.)"));
        let pc = b.pcurve(plane, c2);
        b.add(&format!("SURFACE_CURVE('',#{c3},(#{pc}),.PCURVE_S1.)"))
    } else {
        c3
    };
    let e = b.edge(vh, vh, geometry, true);
    let hole = b.oriented(e, false);
    let bo = b.bound(&outer, true, true);
    let bh = b.bound(&[hole], false, true);
    b.file(&[bh, bo], plane)
}

fn check_plate(loops: &[Vec<NurbsCurve>]) {
    assert_eq!(loops.len(), 2, "outer bound first, then the hole");
    assert_eq!(loops[0].len(), 4);
    let corners = [(0.0, 0.0), (10.0, 0.0), (10.0, 10.0), (0.0, 10.0)];
    for (c, &(u, v)) in loops[0].iter().zip(&corners) {
        assert_eq!(c.degree(), 1);
        assert!(
            c.start_point().distance(Point::new(u, v)) < 1e-12,
            "{:?}",
            c.start_point()
        );
    }
    assert!((loop_area(&loops[0]) - 100.0).abs() < 1e-12);
    let hole_area = loop_area(&loops[1]);
    assert!(
        (hole_area + 4.0 * std::f64::consts::PI).abs() < 1e-12,
        "{hole_area}"
    );
    for c in &loops[1] {
        assert_eq!(c.degree(), 2);
        let (a, b) = c.param_range();
        for i in 0..=40 {
            let p = c.point_at(a + (b - a) * i as f64 / 40.0);
            assert!(
                (p.distance(Point::new(5.0, 5.0)) - 2.0).abs() < 1e-12,
                "{p:?}"
            );
        }
    }
    assert!(loops[1][0].start_point().distance(Point::new(7.0, 5.0)) < 1e-12);
}

#[test]
fn plate_with_a_hole_from_pcurves() {
    check_plate(&closed(one_face(&plate(&FLAT, true))));
}

#[test]
fn plate_with_a_hole_mapped_from_3d_edges_through_a_tilted_plane() {
    let text = plate(&TILTED, false);
    let m = read_step(text.as_bytes()).unwrap();
    assert_eq!(m.faces[0].surface_name, "PLANE");
    let loops = m.faces[0].loops.clone().unwrap();
    // Mapped points carry rounding of the tilted frame: closure within 1e-12.
    check_plate(&closed(loops));
}

#[test]
fn an_edge_off_its_plane_is_refused_not_projected() {
    // The plate's 3-D curves in the tilted plane, the face on the flat one.
    let text = plate(&TILTED, false).replace("PLANE('',#", "PLANE('',#9999);\n#9998=PLANE('',#");
    let text = text.replace(
        "#9999);",
        "#9997);\n#9997=AXIS2_PLACEMENT_3D('',#9996,$,$);\n#9996=CARTESIAN_POINT('',(0.,0.,0.));",
    );
    let m = read_step(text.as_bytes()).unwrap();
    let e = m.faces[0].loops.as_ref().unwrap_err().to_string();
    assert!(e.contains("leaves the face's plane"), "{e}");
}

/// A cylinder of radius 1 about the z axis, `0 <= z <= 2`, as one face bounded by the two
/// circles and the seam; `seam_first` lists the seam's pcurve at `u = 2 pi` first.
fn cylinder(seam_first: bool, start_with_seam: bool) -> String {
    let tau = std::f64::consts::TAU;
    let mut b = Builder::new();
    let ax = b.axis3([0.0; 3], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
    let cyl = b.add(&format!("CYLINDRICAL_SURFACE('',#{ax},1.)"));
    let (v0, v1) = (b.vertex([1.0, 0.0, 0.0]), b.vertex([1.0, 0.0, 2.0]));
    let circle = |b: &mut Builder, z: f64, v: u64| {
        let a = b.axis3([0.0, 0.0, z], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
        let c3 = b.add(&format!("CIRCLE('',#{a},1.)"));
        let l2 = b.line(&[0.0, z], &[1.0, 0.0]);
        let pc = b.pcurve(cyl, l2);
        let sc = b.add(&format!("SURFACE_CURVE('',#{c3},(#{pc}),.PCURVE_S1.)"));
        b.edge(v, v, sc, true)
    };
    let bottom = circle(&mut b, 0.0, v0);
    let top = circle(&mut b, 2.0, v1);
    let l3 = b.line(&[1.0, 0.0, 0.0], &[0.0, 0.0, 1.0]);
    let l_a = b.line(&[0.0, 0.0], &[0.0, 1.0]);
    let l_b = b.line(&[tau, 0.0], &[0.0, 1.0]);
    let (pa, pb) = (b.pcurve(cyl, l_a), b.pcurve(cyl, l_b));
    let (p1, p2) = if seam_first { (pb, pa) } else { (pa, pb) };
    let seam = b.add(&format!("SEAM_CURVE('',#{l3},(#{p1},#{p2}),.PCURVE_S1.)"));
    let se = b.edge(v0, v1, seam, true);
    let (o1, o2, o3, o4) = (
        b.oriented(bottom, true),
        b.oriented(se, true),
        b.oriented(top, false),
        b.oriented(se, false),
    );
    let order = if start_with_seam {
        [o2, o3, o4, o1]
    } else {
        [o1, o2, o3, o4]
    };
    let bo = b.bound(&order, true, true);
    b.file(&[bo], cyl)
}

#[test]
fn cylinder_with_a_seam_takes_one_seam_pcurve_per_use() {
    let tau = std::f64::consts::TAU;
    for seam_first in [false, true] {
        for start_with_seam in [false, true] {
            let m = read_step(cylinder(seam_first, start_with_seam).as_bytes()).unwrap();
            assert_eq!(m.faces[0].surface_name, "CYLINDRICAL_SURFACE");
            let loops = closed(m.faces[0].loops.clone().unwrap());
            assert_eq!(loops.len(), 1);
            assert_eq!(loops[0].len(), 4);
            // The rectangle [0, 2 pi] x [0, 2], counter-clockwise.
            let area = loop_area(&loops[0]);
            assert!((area - 2.0 * tau).abs() < 1e-12, "{area}");
            let us: Vec<f64> = loops[0].iter().map(|c| c.start_point().x).collect();
            assert!(
                us.iter()
                    .all(|&u| u.abs() < 1e-12 || (u - tau).abs() < 1e-12),
                "{us:?}"
            );
        }
    }
}

/// A quarter of the unit cylinder about z, `0 <= u <= pi/2`, `0 <= v <= 1`, whose bottom
/// edge's 3-D curve is the rational quadratic quarter circle (parameter `t` in `[0, 1]`, not
/// the angle) while its pcurve is the `LINE` `v = 0` (parameter `u`): the curves do not share
/// their parameter. `reversed_edge` writes the bottom edge from `(0, 1, 0)` to `(1, 0, 0)`
/// against its curve (`same_sense .F.`), used backwards by the loop.
fn cylinder_quarter(reversed_edge: bool) -> String {
    let h = std::f64::consts::FRAC_PI_2;
    let mut b = Builder::new();
    let ax = b.axis3([0.0; 3], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
    let cyl = b.add(&format!("CYLINDRICAL_SURFACE('',#{ax},1.)"));
    let va = b.vertex([1.0, 0.0, 0.0]);
    let vb = b.vertex([0.0, 1.0, 0.0]);
    let vc = b.vertex([0.0, 1.0, 1.0]);
    let vd = b.vertex([1.0, 0.0, 1.0]);
    let side = |b: &mut Builder, p: [f64; 3], u: f64| {
        let l3 = b.line(&p, &[0.0, 0.0, 1.0]);
        let l2 = b.line(&[u, 0.0], &[0.0, 1.0]);
        let pc = b.pcurve(cyl, l2);
        b.add(&format!("SURFACE_CURVE('',#{l3},(#{pc}),.PCURVE_S1.)"))
    };
    // Bottom: (1, 0, 0) -> (0, 1, 0) on the rational quadratic arc, pcurve the line v = 0.
    let ids = [
        b.point(&[1.0, 0.0, 0.0]),
        b.point(&[1.0, 1.0, 0.0]),
        b.point(&[0.0, 1.0, 0.0]),
    ];
    let arc = b.add(&format!(
        "(BOUNDED_CURVE()B_SPLINE_CURVE(2,({}),.CIRCULAR_ARC.,.F.,.F.)B_SPLINE_CURVE_WITH_KNOTS((3,3),(0.,1.),.UNSPECIFIED.)CURVE()GEOMETRIC_REPRESENTATION_ITEM()RATIONAL_B_SPLINE_CURVE((1.,{:?},1.))REPRESENTATION_ITEM(''))",
        refs(&ids),
        0.5f64.sqrt()
    ));
    let l2 = b.line(&[0.0, 0.0], &[1.0, 0.0]);
    let pc = b.pcurve(cyl, l2);
    let sc = b.add(&format!("SURFACE_CURVE('',#{arc},(#{pc}),.PCURVE_S1.)"));
    let bottom = if reversed_edge {
        let e = b.edge(vb, va, sc, false);
        b.oriented(e, false)
    } else {
        let e = b.edge(va, vb, sc, true);
        b.oriented(e, true)
    };
    // Right: (0, 1, 0) -> (0, 1, 1) at u = pi/2.
    let right = side(&mut b, [0.0, 1.0, 0.0], h);
    let right = b.edge(vb, vc, right, true);
    let right = b.oriented(right, true);
    // Top: the circle at z = 1 (parameter the angle) from (1, 0, 1) to (0, 1, 1), used
    // backwards; pcurve the line v = 1.
    let a1 = b.axis3([0.0, 0.0, 1.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
    let c3 = b.add(&format!("CIRCLE('',#{a1},1.)"));
    let l2 = b.line(&[0.0, 1.0], &[1.0, 0.0]);
    let pc = b.pcurve(cyl, l2);
    let sc = b.add(&format!("SURFACE_CURVE('',#{c3},(#{pc}),.PCURVE_S1.)"));
    let top = b.edge(vd, vc, sc, true);
    let top = b.oriented(top, false);
    // Left: (1, 0, 0) -> (1, 0, 1) at u = 0, used backwards.
    let left = side(&mut b, [1.0, 0.0, 0.0], 0.0);
    let left = b.edge(va, vd, left, true);
    let left = b.oriented(left, false);
    let bo = b.bound(&[bottom, right, top, left], true, true);
    b.file(&[bo], cyl)
}

#[test]
fn a_pcurve_parametrised_unlike_its_3d_curve_is_cut_at_the_vertices_uv() {
    let h = std::f64::consts::FRAC_PI_2;
    for reversed_edge in [false, true] {
        let loops = closed(one_face(&cylinder_quarter(reversed_edge)));
        assert_eq!(loops.len(), 1);
        assert_eq!(loops[0].len(), 4);
        // The bottom runs along v = 0 from u = 0 to u = pi/2 (the same-parameter rule would
        // stop it at u = 1, the arc's parameter at (0, 1, 0)).
        let bottom = &loops[0][0];
        assert_eq!(bottom.degree(), 1);
        assert!(bottom.start_point().distance(Point::new(0.0, 0.0)) < 1e-12);
        assert!(
            bottom.end_point().distance(Point::new(h, 0.0)) < 1e-12,
            "{:?}",
            bottom.end_point()
        );
        // The rectangle [0, pi/2] x [0, 1], counter-clockwise.
        let area = loop_area(&loops[0]);
        assert!((area - h).abs() < 1e-12, "{area}");
    }
}

/// A triangle-like face: a line (0,0)-(4,0), a cubic Bezier (4,0)(4,2)(2,4)(0,4) with an
/// interior knot (two spans after inserting 0.5), and a line back; with B-spline pcurves.
#[test]
fn b_spline_pcurve_keeps_degree_knots_and_points() {
    let mut b = Builder::new();
    let ax = b.axis3([0.0; 3], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
    let plane = b.add(&format!("PLANE('',#{ax})"));
    let (va, vb, vc) = (
        b.vertex([0.0; 3]),
        b.vertex([4.0, 0.0, 0.0]),
        b.vertex([0.0, 4.0, 0.0]),
    );
    let seg = |b: &mut Builder, p: [f64; 2], q: [f64; 2], s: u64, e: u64| {
        let d = [q[0] - p[0], q[1] - p[1]];
        let n = (d[0] * d[0] + d[1] * d[1]).sqrt();
        let d = [d[0] / n, d[1] / n];
        let l3 = b.line(&[p[0], p[1], 0.0], &[d[0], d[1], 0.0]);
        let l2 = b.line(&p, &d);
        let pc = b.pcurve(plane, l2);
        let sc = b.add(&format!("SURFACE_CURVE('',#{l3},(#{pc}),.PCURVE_S1.)"));
        let ed = b.edge(s, e, sc, true);
        b.oriented(ed, true)
    };
    let e1 = seg(&mut b, [0.0, 0.0], [4.0, 0.0], va, vb);
    let e3 = seg(&mut b, [0.0, 4.0], [0.0, 0.0], vc, va);
    // The Bezier with the knot 0.5 inserted: points by de Casteljau at 1/2.
    let pts = [
        [4.0, 0.0],
        [4.0, 1.0],
        [3.5, 2.0],
        [2.75, 2.75],
        [2.0, 3.5],
        [1.0, 4.0],
        [0.0, 4.0],
    ];
    let spline = |b: &mut Builder, dim3: bool| {
        let ids: Vec<u64> = pts
            .iter()
            .map(|p| {
                if dim3 {
                    b.point(&[p[0], p[1], 0.0])
                } else {
                    b.point(p)
                }
            })
            .collect();
        b.add(&format!(
            "B_SPLINE_CURVE_WITH_KNOTS('',3,({}),.UNSPECIFIED.,.F.,.F.,(4,3,4),(0.,0.5,1.),.UNSPECIFIED.)",
            refs(&ids)
        ))
    };
    let s3 = spline(&mut b, true);
    let s2 = spline(&mut b, false);
    let pc = b.pcurve(plane, s2);
    let sc = b.add(&format!("SURFACE_CURVE('',#{s3},(#{pc}),.PCURVE_S1.)"));
    let ed = b.edge(vb, vc, sc, true);
    let e2 = b.oriented(ed, true);
    let bo = b.bound(&[e1, e2, e3], true, true);
    let loops = closed(one_face(&b.file(&[bo], plane)));
    let c = &loops[0][1];
    assert_eq!(c.degree(), 3);
    assert_eq!(
        c.knots().knots(),
        &[0.0, 0.0, 0.0, 0.0, 0.5, 0.5, 0.5, 1.0, 1.0, 1.0, 1.0]
    );
    let want: Vec<Point> = pts.iter().map(|p| Point::new(p[0], p[1])).collect();
    assert_eq!(c.control_points(), want.as_slice());
    // The Bezier at t = 1/2 is (2.75, 2.75). The two lines lie on the axes, so the area is
    // the Bezier's (1/2) integral of x dy - y dx, exactly 61/5.
    assert!(c.point_at(0.5).distance(Point::new(2.75, 2.75)) < 1e-15);
    let area = loop_area(&loops[0]);
    assert!((area - 12.2).abs() < 1e-12, "{area}");
}

/// A disc of radius 2 about the origin bounded by one closed edge: a 3-D circle whose pcurve
/// is a rational B-spline (complex instance), the 7-point form `OpenCASCADE` writes (three
/// 120-degree pieces, middle weights 1/2, unclamped knots).
#[test]
fn rational_complex_instance_pcurve_lies_on_its_circle() {
    let mut b = Builder::new();
    let ax = b.axis3([0.0; 3], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
    let plane = b.add(&format!("PLANE('',#{ax})"));
    let v = b.vertex([2.0, 0.0, 0.0]);
    let c3 = b.add(&format!("CIRCLE('',#{ax},2.)"));
    let s3 = 3f64.sqrt();
    let pts = [
        [2.0, 0.0],
        [2.0, 2.0 * s3],
        [-1.0, s3],
        [-4.0, 0.0],
        [-1.0, -s3],
        [2.0, -2.0 * s3],
        [2.0, 0.0],
    ];
    let ids: Vec<u64> = pts.iter().map(|p| b.point(p)).collect();
    let third = std::f64::consts::TAU / 3.0;
    let c2 = b.add(&format!(
        "(BOUNDED_CURVE()B_SPLINE_CURVE(2,({}),.UNSPECIFIED.,.F.,.F.)B_SPLINE_CURVE_WITH_KNOTS((1,2,2,2,2,1),({:?},0.,{:?},{:?},{:?},{:?}),.UNSPECIFIED.)CURVE()GEOMETRIC_REPRESENTATION_ITEM()RATIONAL_B_SPLINE_CURVE((1.,0.5,1.,0.5,1.,0.5,1.))REPRESENTATION_ITEM(''))",
        refs(&ids),
        -third,
        third,
        2.0 * third,
        std::f64::consts::TAU,
        std::f64::consts::TAU + third
    ));
    let pc = b.pcurve(plane, c2);
    let sc = b.add(&format!("SURFACE_CURVE('',#{c3},(#{pc}),.PCURVE_S1.)"));
    let e = b.edge(v, v, sc, true);
    let oe = b.oriented(e, true);
    let bo = b.bound(&[oe], true, true);
    let loops = closed(one_face(&b.file(&[bo], plane)));
    let mut n = 0;
    for c in &loops[0] {
        assert_eq!(c.degree(), 2);
        let (a, b) = c.param_range();
        for i in 0..=60 {
            let p = c.point_at(a + (b - a) * i as f64 / 60.0);
            assert!((p.length() - 2.0).abs() < 1e-12, "{p:?}");
            n += 1;
        }
    }
    assert!(n > 0);
    let area = loop_area(&loops[0]);
    assert!((area - 4.0 * std::f64::consts::PI).abs() < 1e-12, "{area}");
}

/// The unit square's loop with every combination of the three orientation flags: the edges
/// and their curves are written so that the edge loop is the counter-clockwise square
/// whatever the edge and curve flags; the bound's `.F.` reverses it.
#[test]
fn the_three_orientation_flags_compose() {
    let corners = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    for bits in 0..8u32 {
        let (bound_fwd, oe_fwd, same) = (bits & 1 == 0, bits & 2 == 0, bits & 4 == 0);
        for pcurves in [true, false] {
            let mut b = Builder::new();
            let ax = b.axis3([0.0; 3], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
            let plane = b.add(&format!("PLANE('',#{ax})"));
            let vs: Vec<u64> = corners
                .iter()
                .map(|c| b.vertex([c[0], c[1], 0.0]))
                .collect();
            let mut oes = Vec::new();
            for i in 0..4 {
                let (p, q) = (i, (i + 1) % 4);
                // The edge runs p -> q when the oriented edge is forward, else q -> p.
                let (s, e) = if oe_fwd { (p, q) } else { (q, p) };
                // Its curve runs with the edge when same_sense, else against it.
                let (from, to) = if same { (s, e) } else { (e, s) };
                let d = [
                    corners[to][0] - corners[from][0],
                    corners[to][1] - corners[from][1],
                ];
                let l3 = b.line(
                    &[corners[from][0], corners[from][1], 0.0],
                    &[d[0], d[1], 0.0],
                );
                let geometry = if pcurves {
                    let l2 = b.line(&corners[from], &d);
                    let pc = b.pcurve(plane, l2);
                    b.add(&format!("SURFACE_CURVE('',#{l3},(#{pc}),.PCURVE_S1.)"))
                } else {
                    l3
                };
                let ed = b.edge(vs[s], vs[e], geometry, same);
                oes.push(b.oriented(ed, oe_fwd));
            }
            let bo = b.bound(&oes, true, bound_fwd);
            let m = read_step(b.file(&[bo], plane).as_bytes()).unwrap();
            let loops = m.faces[0]
                .loops
                .clone()
                .unwrap_or_else(|e| panic!("flags {bits:03b} pcurves {pcurves}: {e}"));
            let loops = closed(loops);
            let area = loop_area(&loops[0]);
            // The edge loop itself always chains counter-clockwise; the bound's .F. reverses it.
            let want = if bound_fwd { 1.0 } else { -1.0 };
            assert!(
                (area - want).abs() < 1e-12,
                "flags {bits:03b} pcurves {pcurves}: {area}"
            );
        }
    }
}

#[test]
fn a_wrong_same_sense_is_an_error_naming_the_edge() {
    let text = plate(&FLAT, true);
    // The first square edge claims its line runs against it.
    let first_edge = text.find("EDGE_CURVE(").unwrap();
    let end = first_edge + text[first_edge..].find(".T.)").unwrap();
    let mut t = text.clone();
    t.replace_range(end..end + 3, ".F.");
    let m = read_step(t.as_bytes()).unwrap();
    let e = m.faces[0].loops.as_ref().unwrap_err().to_string();
    assert!(e.contains("EDGE_CURVE"), "{e}");
    assert!(!e.to_string().contains('\n'));
}

#[test]
fn a_face_without_pcurves_on_a_cylinder_gets_exact_iso_lines() {
    let tau = std::f64::consts::TAU;
    let text = cylinder(false, false);
    // Replace the circles' SURFACE_CURVEs by their bare 3-D curves.
    let mut t = String::new();
    for line in text.lines() {
        if line.contains("SURFACE_CURVE('',#") {
            let (id, rest) = line.split_once('=').unwrap();
            let c3 = rest.split("',").nth(1).unwrap().split(',').next().unwrap();
            t += &format!("{id}=CONIC_PLACEHOLDER{c3};\n");
        } else {
            t += line;
            t += "\n";
        }
    }
    // A bare curve as edge geometry: point the edges straight at the circles.
    let t = fix_placeholders(&t);
    let m = read_step(t.as_bytes()).unwrap();
    let f = &m.faces[0];
    let loops = closed(f.loops.clone().unwrap());
    // The circles are the lines v = 0 and v = 2 (iso-lines, exact: no fitted bound).
    assert!(f.pcurve_deviation.is_none());
    assert!((loop_area(&loops[0]) - 2.0 * tau).abs() < 1e-12);
    for c in &loops[0] {
        let (a, b) = (c.start_point(), c.end_point());
        let horizontal = (a.y - b.y).abs() < 1e-15;
        assert!(horizontal || (a.x - b.x).abs() < 1e-15, "{a:?} {b:?}");
        if horizontal {
            assert!(a.y.abs() < 1e-15 || (a.y - 2.0).abs() < 1e-15, "{a:?}");
        }
    }
    // On a surface the reader does not know, no pcurve can be computed.
    let t = t.replace(
        "CYLINDRICAL_SURFACE('',",
        "CYLINDRICAL_SURFACE_OF_SOMETHING('',",
    );
    let m = read_step(t.as_bytes()).unwrap();
    let e = m.faces[0].loops.as_ref().unwrap_err().to_string();
    assert!(
        e.contains("has no pcurve on its CYLINDRICAL_SURFACE_OF_SOMETHING #")
            && e.contains("could not be read to compute one"),
        "{e}"
    );
}

/// Rewrites `#n=CONIC_PLACEHOLDER#m;` into a reference to `#m` wherever `#n` is used.
fn fix_placeholders(t: &str) -> String {
    let mut map = Vec::new();
    let mut out = String::new();
    for line in t.lines() {
        if let Some((id, target)) = line.split_once("=CONIC_PLACEHOLDER") {
            map.push((
                format!("{id},"),
                format!("{},", target.trim_end_matches(';')),
            ));
        } else {
            out += line;
            out += "\n";
        }
    }
    for (from, to) in map {
        out = out.replace(&from, &to);
    }
    out
}

// ---------------------------------------------------------------------------------------
// Hostile input

/// Reads `text`; every problem must be a one-line message, at file or face level.
fn hostile(name: &str, text: &[u8]) -> String {
    match read_step(text) {
        Err(e) => {
            let m = e.to_string();
            assert!(!m.contains('\n'), "{name}: {m}");
            m
        }
        Ok(m) => {
            let errs: Vec<String> = m
                .faces
                .iter()
                .filter_map(|f| f.loops.as_ref().err().map(ToString::to_string))
                .collect();
            assert!(!errs.is_empty(), "{name}: no error");
            for e in &errs {
                assert!(!e.to_string().contains('\n'), "{name}: {e}");
            }
            errs.join(" | ")
        }
    }
}

#[test]
fn truncated_files_are_errors() {
    let text = plate(&FLAT, true);
    let bytes = text.as_bytes();
    // Every cut: an error or (cut after the end marker) a good file, never a panic.
    for cut in (0..bytes.len()).step_by(7) {
        let r = read_step(&bytes[..cut]);
        if let Err(e) = r {
            assert!(!e.to_string().contains('\n'));
        } else {
            panic!("cut at {cut} of {} read", bytes.len());
        }
    }
    let m = hostile("half", &bytes[..bytes.len() / 2]);
    assert!(
        m.contains("ends early") || m.contains("unterminated"),
        "{m}"
    );
}

#[test]
fn unterminated_string_and_comment() {
    let m = hostile(
        "string",
        step_file("#1=PRODUCT('abc,'p','',());").as_bytes(),
    );
    assert!(
        m.contains("unterminated string") || m.contains("line"),
        "{m}"
    );
    let t = step_file("#1=PRODUCT('p','p','',()); /* open").replace("ENDSEC;\nEND", "");
    let m = hostile("comment", t.as_bytes());
    assert!(m.contains("unterminated comment"), "{m}");
}

#[test]
fn missing_references() {
    // The shell names a face that is not there: the structure is broken.
    let t = step_file("#100=OPEN_SHELL('',(#99));");
    let m = hostile("missing face", t.as_bytes());
    assert!(m.contains("#99") && m.contains("not in the file"), "{m}");
    // The face names a missing surface: that face is refused.
    let t = plate(&FLAT, true).replace("#99=ADVANCED_FACE('',(", "#99=ADVANCED_FACE('',(#77777,");
    let m = hostile("missing bound", t.as_bytes());
    assert!(m.contains("#77777"), "{m}");
}

#[test]
fn reference_cycles() {
    // An oriented edge whose element is itself.
    let mut b = Builder::new();
    let ax = b.axis3([0.0; 3], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
    let plane = b.add(&format!("PLANE('',#{ax})"));
    b.text += "#150=ORIENTED_EDGE('',*,*,#150,.T.);\n";
    let bo = b.bound(&[150], true, true);
    let m = hostile("self edge", b.file(&[bo], plane).as_bytes());
    assert!(m.contains("#150"), "{m}");
    // An edge loop that contains itself through an oriented edge.
    let t = step_file(
        "#99=ADVANCED_FACE('',(#98),#97,.T.);#98=FACE_BOUND('',#96,.T.);#96=EDGE_LOOP('',(#95));         #95=ORIENTED_EDGE('',*,*,#96,.T.);#97=PLANE('',#94);#94=AXIS2_PLACEMENT_3D('',#93,$,$);         #93=CARTESIAN_POINT('',(0.,0.,0.));#100=OPEN_SHELL('',(#99));",
    );
    let m = hostile("loop cycle", t.as_bytes());
    assert!(m.contains("#96"), "{m}");
    // Shells and mapped items that contain themselves.
    let t = step_file(
        "#100=ORIENTED_CLOSED_SHELL('',*,#101,.T.);#101=ORIENTED_CLOSED_SHELL('',*,#100,.F.);",
    );
    let m = hostile("shell cycle", t.as_bytes());
    assert!(m.contains("cycle"), "{m}");
    let t = step_file(
        "#100=OPEN_SHELL('',(#102));#102=MAPPED_ITEM('',#103,#104);#103=REPRESENTATION_MAP(#104,#9006);",
    );
    // The mapped item points back at the representation being walked.
    let m = hostile("mapped item cycle", t.as_bytes());
    assert!(m.contains("cycle"), "{m}");
    // Products that contain themselves.
    let t = step_file(
        "#100=OPEN_SHELL('',());#120=NEXT_ASSEMBLY_USAGE_OCCURRENCE('','','',#9001,#121,$);         #121=PRODUCT_DEFINITION('design','',#9023,#9024);         #122=NEXT_ASSEMBLY_USAGE_OCCURRENCE('','','',#121,#9001,$);",
    );
    // #9001 and #121 are both components: no root, nothing to read, fallback finds no face.
    assert!(read_step(t.as_bytes()).unwrap().faces.is_empty());
    let t = step_file(
        "#100=OPEN_SHELL('',());#120=NEXT_ASSEMBLY_USAGE_OCCURRENCE('','','',#9001,#121,$);         #121=PRODUCT_DEFINITION('design','',#9023,#9024);         #122=NEXT_ASSEMBLY_USAGE_OCCURRENCE('','','',#121,#121,$);         #123=PRODUCT_DEFINITION('design','',#9023,#9024);         #124=NEXT_ASSEMBLY_USAGE_OCCURRENCE('','','',#123,#9001,$);",
    );
    let m = hostile("assembly cycle", t.as_bytes());
    assert!(m.contains("contains itself"), "{m}");
}

#[test]
fn deep_nesting_and_a_flood_of_parentheses() {
    let deep = format!(
        "#1=PRODUCT('p','p','',{}{});",
        "(".repeat(10_000),
        ")".repeat(10_000)
    );
    let m = hostile("deep", step_file(&deep).as_bytes());
    assert!(m.contains("nested deeper"), "{m}");
    let mut flood = step_file("#1=PRODUCT('p','p','',").into_bytes();
    flood.truncate(flood.len() - 40);
    flood.extend(std::iter::repeat_n(b'(', 100 << 20));
    let t0 = std::time::Instant::now();
    let m = hostile("flood", &flood);
    assert!(m.contains("nested deeper") || m.contains("line"), "{m}");
    assert!(t0.elapsed().as_secs() < 10);
}

#[test]
fn a_b_spline_claiming_a_trillion_points() {
    let t = plate(&FLAT, true);
    let mut b = Builder::new();
    b.next = 5000;
    let p = b.point(&[0.0, 0.0]);
    let q = b.point(&[1.0, 0.0]);
    b.add(&format!(
        "B_SPLINE_CURVE_WITH_KNOTS('',3,(#{p},#{q}),.UNSPECIFIED.,.F.,.F.,(1000000000000,4),(0.,1.),.UNSPECIFIED.)"
    ));
    // Make the hole's pcurve that spline.
    let hole_pc = t.find("CIRCLE('',#").map(|_| ()).is_some();
    assert!(hole_pc);
    let idx = t.rfind("DEFINITIONAL_REPRESENTATION('',(#").unwrap();
    let start = idx + "DEFINITIONAL_REPRESENTATION('',(#".len();
    let stop = start + t[start..].find(')').unwrap();
    let mut t2 = t.clone();
    t2.replace_range(start..stop, "5002");
    let t2 = t2.replace("ENDSEC;\nEND", &format!("{}ENDSEC;\nEND", b.text));
    let m = hostile("huge multiplicity", t2.as_bytes());
    assert!(m.contains("#5002"), "{m}");
}

#[test]
fn non_finite_numbers_and_wrong_types() {
    let t = plate(&FLAT, true).replacen("2.)", "1E400)", 1);
    let m = hostile("1e400", t.as_bytes());
    assert!(m.contains("not finite"), "{m}");
    let t = plate(&FLAT, true).replacen("CARTESIAN_POINT('',(0.0", "CARTESIAN_POINT('',(NaN", 1);
    hostile("NaN", t.as_bytes());
    let t = plate(&FLAT, true).replacen("CIRCLE('',#", "CIRCLE('',", 1);
    hostile("CIRCLE without its placement reference", t.as_bytes());
    let t = plate(&FLAT, true).replacen(",2.)", ",'two')", 1);
    let m = hostile("radius string", t.as_bytes());
    assert!(m.contains("CIRCLE") && m.contains("radius"), "{m}");
    let t = plate(&FLAT, true).replacen("VERTEX_POINT('',#", "VERTEX_POINT('',.T.,#", 1);
    let m = hostile("vertex enum", t.as_bytes());
    assert!(m.contains("VERTEX_POINT"), "{m}");
}

/// The expected face counts (`OpenCASCADE` 7.8's face explorer on the same files).
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
    let tol = m.tolerance.chain_gap();
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
                assert!(!e.to_string().contains('\n'), "{name}: {e}");
                eprintln!("{name} face {k} {} ({}): {e}", f.entity, f.surface_name);
            }
        }
    }
    (ok, refused)
}

#[test]
fn idflibs_every_face_reads_and_every_loop_closes() {
    let mut total = 0;
    for (file, faces) in IDF_FACES {
        let path = format!("{IDF}/{file}");
        let Some(text) = rs_testkit::system_file(&path, "freecad") else {
            return;
        };
        let m = read_step(&text).unwrap_or_else(|e| panic!("{file}: {e}"));
        assert_eq!(m.faces.len(), faces, "{file}");
        assert!(m.tolerance.stated().is_some(), "{file}");
        let (ok, refused) = check_real(file, &m);
        eprintln!(
            "{file}: {ok} read, {refused} refused, max gap {:e}",
            max_gap(&m)
        );
        assert_eq!(refused, 0, "{file}");
        assert!(m.face_domains(None).iter().all(Result::is_ok), "{file}");
        total += ok;
    }
    eprintln!("Idflibs: {total} faces read");
    assert_eq!(total, 2849);
}

/// `SMB_DO_214AA`'s faces 38 and 40 (and `SMC_DO_214AB`'s): their `LINE` edges at `z = 2.3` end on
/// vertices at `z = 2.3025`, so the pcurves of a line and of the next edge (through the
/// vertex) leave a gap of 2.5e-3 in the plane, beyond the chain gap (2e-3); `OpenCASCADE`
/// reads them (its edge tolerance there is 2.5e-3). The gap is the line's own miss of the
/// vertex the two edges share, and a segment bridges it.
#[test]
fn a_gap_an_edge_leaves_at_its_shared_vertex_is_bridged() {
    for file in ["SMB_DO_214AA.stp", "SMC_DO_214AB.stp"] {
        let path = format!("{IDF}/{file}");
        let Some(text) = rs_testkit::system_file(&path, "freecad") else {
            return;
        };
        let m = read_step(&text).unwrap();
        for k in [38, 40] {
            let f = &m.faces[k];
            let loops = f.loops.as_ref().unwrap();
            // A bridge: a degree-1 curve 2.5e-3 long, where no edge is.
            let bridges: Vec<f64> = loops
                .iter()
                .flatten()
                .filter(|c| c.degree() == 1)
                .map(|c| c.start_point().distance(c.end_point()))
                .filter(|&l| l > 2e-3 && l < 2.6e-3)
                .collect();
            assert!(!bridges.is_empty(), "{file} face {k}");
            let curves: usize = loops.iter().map(Vec::len).sum();
            let edges: usize = f.edges.iter().map(Vec::len).sum();
            assert!(curves > edges, "{file} face {k}");
            assert!(m.face_domain(k, None).is_ok(), "{file} face {k}");
        }
    }
    // A gap the edges' curves do not explain is not bridged: the plate's second side with its
    // pcurve moved 3e-3 off (its 3-D line ends on its vertices).
    let text = plate(&FLAT, true);
    let moved = text.replacen(
        "CARTESIAN_POINT('',(10.0,0.0))",
        "CARTESIAN_POINT('',(10.003,0.0))",
        1,
    );
    assert_ne!(moved, text);
    let m = read_step(moved.as_bytes()).unwrap();
    let e = m.faces[0].loops.as_ref().unwrap_err().to_string();
    assert!(
        e.contains("does not meet the previous edge in (u, v): gap 3.000e-3"),
        "{e}"
    );
}

#[test]
fn the_assembly_lists_each_occurrence_of_its_parts() {
    // Two parts placed in an assembly: the faces of both, each part's in its shell's order,
    // the parts in the order of the file's NEXT_ASSEMBLY_USAGE_OCCURRENCEs (as `OpenCASCADE`).
    let path = format!("{IDF}/I22_2_5_16withEPL22_6_16.stp");
    let Some(text) = rs_testkit::system_file(&path, "freecad") else {
        return;
    };
    let m = read_step(&text).unwrap();
    assert_eq!(m.faces.len(), 72);
    let labels: Vec<u64> = m
        .faces
        .iter()
        .map(|f| f.entity[1..].parse().unwrap())
        .collect();
    assert!(labels.windows(2).all(|w| w[0] < w[1]), "{labels:?}");
}

#[test]
fn as1_assembly_faces_come_in_opencascade_order() {
    // as1: the root assembly places rod-assembly (nut, nut, rod), l-bracket-assembly (three
    // nut-bolt-assemblies (bolt, nut) and the l-bracket), the plate, and a second
    // l-bracket-assembly. `OpenCASCADE` 7.8 lists the parts' faces in exactly this order.
    let Some(text) = gmsh_demo("demos/api/as1-tu-203.stp.gz") else {
        return;
    };
    let m = read_step(&text).unwrap();
    let part = |label: u64| match label {
        197..=293 => "nut",
        399..=441 => "rod",
        621..=705 => "bolt",
        1099..=1343 => "l-bracket",
        1790..=2066 => "plate",
        _ => "?",
    };
    let mut runs: Vec<(&str, usize)> = Vec::new();
    let mut prev = 0u64;
    for f in &m.faces {
        let l: u64 = f.entity[1..].parse().unwrap();
        let p = part(l);
        // A new occurrence starts where the labels stop increasing.
        match runs.last_mut() {
            Some((q, n)) if *q == p && l > prev => *n += 1,
            _ => runs.push((p, 1)),
        }
        prev = l;
    }
    let bracket_assembly = [
        ("bolt", 7),
        ("nut", 8),
        ("bolt", 7),
        ("nut", 8),
        ("bolt", 7),
        ("nut", 8),
        ("l-bracket", 16),
    ];
    let mut want = vec![("nut", 8), ("nut", 8), ("rod", 4)];
    want.extend(bracket_assembly);
    want.push(("plate", 18));
    want.extend(bracket_assembly);
    assert_eq!(runs, want);
}

/// A gzipped gmsh demo decompressed with `gzip -dc`.
fn gmsh_demo(rel: &str) -> Option<Vec<u8>> {
    let path = format!("{GMSH}/{rel}");
    if !std::path::Path::new(&path).exists() {
        rs_testkit::missing_system_files(&path, "gmsh-doc");
        return None;
    }
    let out = std::process::Command::new("gzip")
        .args(["-dc", &path])
        .output()
        .unwrap();
    assert!(out.status.success(), "gzip -dc {path}");
    // Kept in memory: tests running at once decompress the same demo.
    Some(out.stdout)
}

#[test]
fn gmsh_demos_without_pcurves_get_them_from_their_edges() {
    // (file, faces, faces with fitted pcurves): faces as `OpenCASCADE` counts them (as1 is an
    // assembly that places its parts 160 times in all). These files have no pcurves: planes
    // are mapped from their 3-D edges exactly; on as1's rational patches every edge is a
    // boundary iso-line (exact); component8 (= t20_data) has intersection edges off the
    // surface by up to 2.6e-3, fitted within its tolerance of 0.074 (research d).
    for (rel, faces, fitted) in [
        ("demos/api/as1-tu-203.stp.gz", 160, 0),
        ("demos/api/step_boundary_colors.stp.gz", 6, 0),
        ("demos/boolean/component8.step.gz", 21, 15),
        ("tutorial/t20_data.step.gz", 21, 15),
    ] {
        let Some(text) = gmsh_demo(rel) else { return };
        let m = read_step(&text).unwrap_or_else(|e| panic!("{rel}: {e}"));
        assert_eq!(m.faces.len(), faces, "{rel}");
        let (ok, bad) = check_real(rel, &m);
        eprintln!("{rel}: {ok} read, {bad} refused, max gap {:e}", max_gap(&m));
        assert_eq!((ok, bad), (faces, 0), "{rel}");
        let tolerance = m.tolerance.stated().unwrap();
        let bounds: Vec<f64> = m.faces.iter().filter_map(|f| f.pcurve_deviation).collect();
        assert_eq!(bounds.len(), fitted, "{rel}");
        assert!(
            bounds.iter().all(|&d| d > 0.0 && d <= tolerance),
            "{rel}: {bounds:?}"
        );
        for f in &m.faces {
            assert!(
                f.surface_name == "PLANE" || f.surface_name.contains("B_SPLINE_SURFACE"),
                "{rel}: {}",
                f.surface_name
            );
            if f.surface_name == "PLANE" {
                assert!(f.pcurve_deviation.is_none());
            }
        }
        // Every face a domain.
        assert!(m.face_domains(None).iter().all(Result::is_ok), "{rel}");
    }
}

#[test]
fn a_fitted_pcurve_beyond_the_file_s_tolerance_refuses_its_face() {
    let Some(text) = gmsh_demo("demos/boolean/component8.step.gz") else {
        return;
    };
    let text = String::from_utf8(text).unwrap();
    // 1e-4: the intersection edges (up to 2.6e-3 off their surfaces) are near enough to be
    // fitted, but no fit can come within the tolerance of an edge farther from its surface.
    let tight = text.replace("LENGTH_MEASURE(0.0741808824497)", "LENGTH_MEASURE(1.E-04)");
    assert_ne!(tight, text);
    let m = read_step(tight.as_bytes()).unwrap();
    let mut refused = 0;
    for f in &m.faces {
        let Err(FaceError::Read(e)) = &f.loops else {
            assert!(f.pcurve_deviation.is_none_or(|d| d <= 1e-4));
            continue;
        };
        refused += 1;
        let e = e.0.downcast_ref::<StepError>().unwrap();
        let StepError::PcurveDeviation {
            bound, tolerance, ..
        } = e
        else {
            panic!("{e}");
        };
        assert!(*tolerance == 1e-4 && *bound > *tolerance, "{e}");
        let msg = e.to_string();
        assert!(
            msg.starts_with("edge #") && msg.ends_with("more than the file's tolerance 1.000e-4"),
            "{msg}"
        );
    }
    eprintln!("component8 at 1e-4: {refused} faces refused");
    // Faces with intersection edges; the iso-line faces stay exact.
    assert!((1..=15).contains(&refused), "{refused}");
}

// ---------------------------------------------------------------------------------------
// Surfaces, edges, topology and placements

/// A fixture of `fixtures/cad/`.
fn fixture(name: &str) -> Vec<u8> {
    let path = format!("{}/../../fixtures/cad/{name}", env!("CARGO_MANIFEST_DIR"));
    std::fs::read(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// The largest distance from the face's surface at points of its loops (9 per trimming curve)
/// to the nearest of its 3-D edges: how well the `(u, v)` loops and the surface agree with the
/// edges. `None` for a face without loops, surface or edges.
fn surface_to_edges(f: &Face) -> Option<f64> {
    let (Ok(loops), Some(s)) = (&f.loops, &f.surface) else {
        return None;
    };
    let edges: Vec<&Edge> = f.edges.iter().flatten().collect();
    if edges.is_empty() {
        return None;
    }
    let mut worst = 0.0f64;
    for c in loops.iter().flatten() {
        let (a, b) = c.param_range();
        for i in 0..=8 {
            let uv = c.point_at(a + (b - a) * f64::from(i) / 8.0);
            let x = s.point([uv.x, uv.y]);
            let d = edges
                .iter()
                .map(|e| {
                    let t = e.curve.closest_parameter(x, Some(e.range));
                    e.curve.point(t).distance(x)
                })
                .fold(f64::INFINITY, f64::min);
            worst = worst.max(d);
        }
    }
    Some(worst)
}

/// Faces whose own pcurves and 3-D edges disagree by more than their file's stated tolerance,
/// with `OpenCASCADE`'s largest edge tolerance on the face (`BRep_Tool::Tolerance`, OCP 8.0),
/// which bounds the disagreement there: the files' data, not the reader.
const EDGE_TOLERANCES: [(&str, usize, f64); 21] = [
    ("CAP_50SGV_8_10.stp", 18, 1.4977e-4),
    ("CAP_50SGV_8_10.stp", 19, 1.0242e-4),
    ("CAP_50SGV_8_10.stp", 21, 8.0918e-5),
    ("SMB_DO_214AA.stp", 17, 4.7848e-4),
    ("SMB_DO_214AA.stp", 18, 4.7848e-4),
    ("SMB_DO_214AA.stp", 22, 4.7848e-4),
    ("SMB_DO_214AA.stp", 26, 4.7848e-4),
    ("SMB_DO_214AA.stp", 38, 2.50003e-3),
    ("SMB_DO_214AA.stp", 40, 2.50003e-3),
    ("SMB_DO_214AA.stp", 41, 4.37505e-3),
    ("SMB_DO_214AA.stp", 42, 4.37505e-3),
    ("SMB_DO_214AA.stp", 43, 4.37505e-3),
    ("SMC_DO_214AB.stp", 14, 4.7848e-4),
    ("SMC_DO_214AB.stp", 15, 4.7848e-4),
    ("SMC_DO_214AB.stp", 22, 4.7848e-4),
    ("SMC_DO_214AB.stp", 26, 4.7848e-4),
    ("SMC_DO_214AB.stp", 38, 2.50003e-3),
    ("SMC_DO_214AB.stp", 40, 2.50003e-3),
    ("SMC_DO_214AB.stp", 41, 4.37505e-3),
    ("SMC_DO_214AB.stp", 42, 4.37505e-3),
    ("SMC_DO_214AB.stp", 43, 4.37505e-3),
];

/// Every readable face of the model: its surface at its loops lies on its 3-D edges within the
/// file's tolerance (or, for the faces of [`EDGE_TOLERANCES`], `OpenCASCADE`'s edge
/// tolerance). Returns how many faces were checked.
fn check_surfaces_meet_edges(name: &str, m: &CadModel) -> usize {
    let stated = m.tolerance.stated().unwrap_or(0.0);
    let mut checked = 0;
    for (k, f) in m.faces.iter().enumerate() {
        let Some(d) = surface_to_edges(f) else {
            continue;
        };
        checked += 1;
        let bound = EDGE_TOLERANCES
            .iter()
            .find(|e| name.ends_with(e.0) && e.1 == k)
            .map_or(stated, |e| e.2);
        assert!(
            d <= bound,
            "{name} face {k} {} ({}): surface {d:e} off its edges (bound {bound:e})",
            f.entity,
            f.surface_name
        );
    }
    checked
}

#[test]
fn surfaces_at_the_loops_lie_on_the_edges_in_every_real_file() {
    let mut checked = 0;
    for (file, _) in IDF_FACES {
        let path = format!("{IDF}/{file}");
        let Some(text) = rs_testkit::system_file(&path, "freecad") else {
            return;
        };
        let m = read_step(&text).unwrap();
        checked += check_surfaces_meet_edges(file, &m);
    }
    for rel in [
        "demos/api/as1-tu-203.stp.gz",
        "demos/api/step_boundary_colors.stp.gz",
        "demos/boolean/component8.step.gz",
        "tutorial/t20_data.step.gz",
    ] {
        let Some(text) = gmsh_demo(rel) else { return };
        let m = read_step(&text).unwrap();
        checked += check_surfaces_meet_edges(rel, &m);
    }
    for name in ["cone_minus_sphere.step", "box_void.step"] {
        let m = read_step(&fixture(name)).unwrap();
        checked += check_surfaces_meet_edges(name, &m);
    }
    // The readable faces (natural-bounds faces have no edges to meet).
    assert_eq!(checked, 2849 + 160 + 6 + 21 + 21 + 3 + 6, "faces checked");
}

/// A whole sphere of radius 2 about (1, 2, 3) bounded by a `VERTEX_LOOP` at its south pole
/// only, as `OpenCASCADE` writes it.
fn whole_sphere(surface: &str) -> String {
    let mut b = Builder::new();
    let ax = b.axis3([1.0, 2.0, 3.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
    let s = b.add(&format!("{surface}('',#{ax},2.)"));
    let v = b.vertex([1.0, 2.0, 1.0]);
    let l = b.add(&format!("VERTEX_LOOP('',#{v})"));
    let bo = b.add(&format!("FACE_BOUND('',#{l},.T.)"));
    b.file(&[bo], s)
}

#[test]
fn a_whole_sphere_takes_its_natural_box_as_opencascade_s_wire() {
    use std::f64::consts::{FRAC_PI_2, PI, TAU};
    let m = read_step(whole_sphere("SPHERICAL_SURFACE").as_bytes()).unwrap();
    let f = &m.faces[0];
    assert!(f.natural_bounds && f.edges.iter().all(Vec::is_empty));
    let loops = closed(f.loops.clone().unwrap());
    assert_eq!(loops.len(), 1);
    // The seam down at u = 0, the south pole, the seam up at u = 2 pi, the north pole.
    let corners = [
        (0.0, FRAC_PI_2),
        (0.0, -FRAC_PI_2),
        (TAU, -FRAC_PI_2),
        (TAU, FRAC_PI_2),
    ];
    for (c, &(u, v)) in loops[0].iter().zip(&corners) {
        assert_eq!(c.degree(), 1);
        assert_eq!(c.start_point(), Point::new(u, v));
    }
    assert!((loop_area(&loops[0]) - TAU * PI).abs() < 1e-12);
    let s = f.surface.as_ref().unwrap();
    // Both poles and the seam are where ISO 10303-42 puts them.
    assert!(
        s.point([0.3, FRAC_PI_2])
            .distance(Point3::new(1.0, 2.0, 5.0))
            < 1e-15
    );
    assert!(
        s.point([5.0, -FRAC_PI_2])
            .distance(Point3::new(1.0, 2.0, 1.0))
            < 1e-15
    );
    assert!(s.point([TAU, 0.0]).distance(Point3::new(3.0, 2.0, 3.0)) < 1e-15);
    // The face's domain is the whole box.
    let d = m.face_domain(0, None).unwrap();
    assert!((d.signed_area() - TAU * PI).abs() < 1e-12);
    // A torus written so: the square of its two angles.
    let torus = whole_sphere("SPHERICAL_SURFACE").replace(
        "SPHERICAL_SURFACE('',#203,2.)",
        "TOROIDAL_SURFACE('',#203,3.,1.)",
    );
    let m = read_step(torus.as_bytes()).unwrap();
    assert_eq!(m.faces[0].surface_name, "TOROIDAL_SURFACE");
    assert!(m.faces[0].natural_bounds);
    let b = m.faces[0].loops_box().unwrap();
    assert_eq!((b.min, b.max), (Point::new(0.0, 0.0), Point::new(TAU, TAU)));
}

#[test]
fn a_face_without_bounds_on_an_unbounded_surface_is_a_typed_error() {
    for (surface, text) in [
        ("CYLINDRICAL_SURFACE", whole_sphere("CYLINDRICAL_SURFACE")),
        ("PLANE", {
            let mut b = Builder::new();
            let ax = b.axis3([0.0; 3], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
            let s = b.add(&format!("PLANE('',#{ax})"));
            b.file(&[], s)
        }),
    ] {
        let m = read_step(text.as_bytes()).unwrap();
        let FaceError::Read(e) = m.faces[0].loops.as_ref().unwrap_err() else {
            panic!("{surface}: not a reader's error");
        };
        let e = e.0.downcast_ref::<StepError>().unwrap();
        assert!(
            matches!(e, StepError::UnboundedFace { surface: s, .. } if s == surface),
            "{e}"
        );
        let msg = e.to_string();
        assert!(
            msg.starts_with("#99 ADVANCED_FACE: a face with no bounds on an unbounded ")
                && msg.contains(&format!("{surface} #"))
                && !msg.contains('\n'),
            "{msg}"
        );
    }
}

#[test]
fn the_sphere_cap_through_the_seam_closes_at_the_pole() {
    use std::f64::consts::{FRAC_PI_2, TAU};
    // OCC's loop of the dimple: the circle, the seam twice; its seam pcurves are written a
    // period off in v (v = t - 2 pi for the circle parameter t in [3 pi/2, 2 pi - 0.725]).
    let m = read_step(&fixture("cone_minus_sphere.step")).unwrap();
    assert_eq!(m.faces.len(), 3);
    let f = &m.faces[1];
    assert_eq!(f.surface_name, "SPHERICAL_SURFACE");
    assert!(!f.same_sense && !f.natural_bounds);
    let loops = closed(f.loops.clone().unwrap());
    assert_eq!(loops.len(), 1);
    // The rectangle [0, 2 pi] x [-pi/2, v0]: circle, seam, pole segment, seam.
    let v0 = -0.725255469595;
    assert_eq!(loops[0].len(), 4);
    let b = f.loops_box().unwrap();
    for (got, want) in [
        (b.min.x, 0.0),
        (b.max.x, TAU),
        (b.min.y, -FRAC_PI_2),
        (b.max.y, v0),
    ] {
        assert!((got - want).abs() < 1e-9, "{b:?}");
    }
    let area = loop_area(&loops[0]).abs();
    assert!((area - TAU * (v0 + FRAC_PI_2)).abs() < 1e-9, "{area}");
    // One of the curves is the pole (the whole segment is the point (0, 0, 1.8)).
    let s = f.surface.as_ref().unwrap();
    let pole = loops[0]
        .iter()
        .find(|c| c.start_point().y.abs() > 1.5 && c.end_point().y.abs() > 1.5)
        .unwrap();
    for t in [0.0, 0.3, 1.0] {
        let uv = pole.point_at(t);
        assert!(s.point([uv.x, uv.y]).distance(Point3::new(0.0, 0.0, 1.8)) < 1e-12);
    }
    // Its 3-D edges: the circle and the seam used twice (in the bound's reversed order).
    let edges: Vec<&str> = f.edges[0].iter().map(|e| e.entity.as_str()).collect();
    assert_eq!(edges, ["#110", "#110", "#21"]);
    assert!(surface_to_edges(f).unwrap() < 1e-12);
}

/// The outward normal of face `f` at the middle of its loops' box.
fn outward(f: &Face) -> (Point3, Point3) {
    let b = f.loops_box().unwrap();
    let uv = [0.5 * (b.min.x + b.max.x), 0.5 * (b.min.y + b.max.y)];
    let s = f.surface.as_ref().unwrap();
    let n = s.normal(uv).unwrap();
    (s.point(uv), if f.same_sense { n } else { n * -1.0 })
}

#[test]
fn a_void_is_a_reversed_shell_of_its_solid() {
    // The cube [-2, 2]^3 with a spherical void: BREP_WITH_VOIDS(outer, (ORIENTED_CLOSED_SHELL .F.)).
    let m = read_step(&fixture("box_void.step")).unwrap();
    assert_eq!(m.faces.len(), 7);
    assert_eq!(m.solids.len(), 1);
    assert_eq!(m.solids[0].entity, "#15");
    assert_eq!(m.solids[0].shells, [0, 1]);
    assert_eq!(m.shells[0].faces, (0..6).collect::<Vec<_>>());
    assert_eq!(m.shells[1].faces, [6]);
    assert!(m.shells.iter().all(|s| s.closed));
    // The void: a whole sphere (natural bounds), its face reversed by its shell.
    let sphere = &m.faces[6];
    assert!(sphere.natural_bounds && !sphere.same_sense);
    let Some(Surface::Sphere(s)) = &sphere.surface else {
        panic!("{:?}", sphere.surface);
    };
    let c = s.frame().origin;
    // Outward normals of the solid: away from the cube's centre on its faces, towards the
    // void's centre on the sphere.
    let centre = Point3::ORIGIN;
    for f in &m.faces[..6] {
        let (p, n) = outward(f);
        assert!((p - centre).dot(n) > 1.0, "{}", f.entity);
    }
    let (p, n) = outward(sphere);
    assert!((p - c).dot(n) < -0.5, "{p:?} {n:?}");
}

#[test]
fn a_closed_shell_with_free_edges_is_no_solid() {
    // The cone_minus_sphere solid without its plane face: its two circle edges are used once.
    let text = String::from_utf8(fixture("cone_minus_sphere.step")).unwrap();
    let open = text.replace(
        "#16 = CLOSED_SHELL('',(#17,#105,#134));",
        "#16 = CLOSED_SHELL('',(#17,#105));",
    );
    assert_ne!(open, text);
    let m = read_step(open.as_bytes()).unwrap();
    assert_eq!(m.faces.len(), 2);
    assert!(m.solids.is_empty());
    assert_eq!(m.shells.len(), 1);
    assert!(!m.shells[0].closed);
    // The whole part is a solid.
    let m = read_step(text.as_bytes()).unwrap();
    assert_eq!(m.solids.len(), 1);
    assert!(m.shells[0].closed);
    // An OPEN_SHELL as a solid's outer shell is no solid either.
    let m = read_step(
        text.replace("#16 = CLOSED_SHELL(", "#16 = OPEN_SHELL(")
            .as_bytes(),
    )
    .unwrap();
    assert!(m.solids.is_empty() && m.shells.len() == 1 && !m.shells[0].closed);
}

#[test]
fn an_oriented_face_reverses_the_face() {
    let text = plate(&FLAT, true);
    let m = read_step(text.as_bytes()).unwrap();
    assert!(m.faces[0].same_sense);
    let t = text.replace(
        "#100=OPEN_SHELL('',(#99));",
        "#100=OPEN_SHELL('',(#98));\n#98=ORIENTED_FACE('',*,#99,.F.);",
    );
    let m = read_step(t.as_bytes()).unwrap();
    assert_eq!(m.faces.len(), 1);
    assert!(!m.faces[0].same_sense);
    // The loops do not change.
    assert_eq!(
        m.faces[0].loops.as_ref().unwrap(),
        read_step(text.as_bytes()).unwrap().faces[0]
            .loops
            .as_ref()
            .unwrap()
    );
}

#[test]
fn a_degenerate_placement_is_an_error_naming_it() {
    // The plane's reference direction along its axis.
    let text = plate(&FLAT, true);
    let at = text.find("=PLANE('',#").unwrap();
    let ax: u64 = text[at + 11..].split(')').next().unwrap().parse().unwrap();
    let line = text
        .lines()
        .find(|l| l.starts_with(&format!("#{ax}=AXIS2_PLACEMENT_3D(")))
        .unwrap();
    // #ax=AXIS2_PLACEMENT_3D('',#point,#axis,#ref);
    let parts: Vec<&str> = line.split(",#").collect();
    assert_eq!(parts.len(), 4, "{line}");
    let bad = format!("{},#{},#{},#{});", parts[0], parts[1], parts[2], parts[2]);
    let m = read_step(text.replace(line, &bad).as_bytes()).unwrap();
    let e = m.faces[0].surface_error.as_ref().unwrap().to_string();
    assert_eq!(
        e,
        format!(
            "#{ax} AXIS2_PLACEMENT_3D: degenerate axes: the reference direction is along the axis"
        )
    );
    assert!(m.faces[0].surface.is_none());
    // The face is refused for it.
    assert_eq!(m.faces[0].loops.as_ref().unwrap_err().to_string(), e);
    // A surface type the reader does not know leaves the pcurves readable.
    let t = text.replace("=PLANE('',#", "=SPHERICAL_SURFACE_OF_SOMETHING('',#");
    let m = read_step(t.as_bytes()).unwrap();
    let e = m.faces[0].surface_error.as_ref().unwrap().to_string();
    assert!(
        e.ends_with("surface type SPHERICAL_SURFACE_OF_SOMETHING is not supported"),
        "{e}"
    );
    assert_eq!(m.faces[0].loops.as_ref().unwrap().len(), 2);
    // The hole's pcurve, a circle on a placement with a zero reference direction: the face's
    // loops name the placement.
    let centre = text.find("CARTESIAN_POINT('',(5.0,5.0))").unwrap();
    let t = text[..centre].to_string()
        + &text[centre..].replacen("DIRECTION('',(1.0,0.0))", "DIRECTION('',(0.0,0.0))", 1);
    assert_ne!(t, text);
    let m = read_step(t.as_bytes()).unwrap();
    let e = m.faces[0].loops.as_ref().unwrap_err().to_string();
    assert!(
        e.contains("AXIS2_PLACEMENT_2D: degenerate axes: the reference direction is zero")
            && !e.contains('\n'),
        "{e}"
    );
}

#[test]
fn cycles_between_shells_and_solids_are_errors() {
    let m = hostile(
        "void cycle",
        step_file(
            "#100=BREP_WITH_VOIDS('',#101,(#102));#101=CLOSED_SHELL('',());#102=ORIENTED_CLOSED_SHELL('',*,#102,.F.);",
        )
        .replace("SHELL_BASED_SURFACE_MODEL('',(#100))", "SHELL_BASED_SURFACE_MODEL('',(#103))")
        .replace("#9007=", "#103=OPEN_SHELL('',());\n#9007=")
        .replace("(#9007),#9010)", "(#9007,#100),#9010)")
        .as_bytes(),
    );
    assert!(m.contains("#102") && m.contains("cycle"), "{m}");
}

/// The plate as the one part of an assembly placed twice: by a translation (10, 0, 0), and by
/// the frame at (0, 5, 0) with axis x and reference y.
fn placed_plates() -> String {
    let part = plate(&FLAT, true);
    let assembly = "#9008=AXIS2_PLACEMENT_3D('',#9040,$,$);
#9040=CARTESIAN_POINT('',(0.,0.,0.));
#8001=PRODUCT_DEFINITION('design','',#9023,#9024);
#8002=PRODUCT_DEFINITION_SHAPE('','',#8001);
#8003=SHAPE_DEFINITION_REPRESENTATION(#8002,#8006);
#8006=SHAPE_REPRESENTATION('',(#8010,#8011,#8012),#9010);
#8010=AXIS2_PLACEMENT_3D('',#9040,$,$);
#8011=AXIS2_PLACEMENT_3D('',#8013,$,$);
#8013=CARTESIAN_POINT('',(10.,0.,0.));
#8012=AXIS2_PLACEMENT_3D('',#8014,#8015,#8016);
#8014=CARTESIAN_POINT('',(0.,5.,0.));
#8015=DIRECTION('',(1.,0.,0.));
#8016=DIRECTION('',(0.,1.,0.));
#8020=NEXT_ASSEMBLY_USAGE_OCCURRENCE('1','','',#8001,#9001,$);
#8021=NEXT_ASSEMBLY_USAGE_OCCURRENCE('2','','',#8001,#9001,$);
#8030=PRODUCT_DEFINITION_SHAPE('','',#8020);
#8031=PRODUCT_DEFINITION_SHAPE('','',#8021);
#8040=CONTEXT_DEPENDENT_SHAPE_REPRESENTATION(#8050,#8030);
#8041=CONTEXT_DEPENDENT_SHAPE_REPRESENTATION(#8051,#8031);
#8050=(REPRESENTATION_RELATIONSHIP('','',#9006,#8006)REPRESENTATION_RELATIONSHIP_WITH_TRANSFORMATION(#8060)SHAPE_REPRESENTATION_RELATIONSHIP());
#8051=(REPRESENTATION_RELATIONSHIP('','',#9006,#8006)REPRESENTATION_RELATIONSHIP_WITH_TRANSFORMATION(#8061)SHAPE_REPRESENTATION_RELATIONSHIP());
#8060=ITEM_DEFINED_TRANSFORMATION('','',#9008,#8011);
#8061=ITEM_DEFINED_TRANSFORMATION('','',#9008,#8012);
";
    part.replace("ENDSEC;\nEND-ISO", &format!("{assembly}ENDSEC;\nEND-ISO"))
}

#[test]
fn assembly_occurrences_place_surfaces_and_edges_not_loops() {
    let part = read_step(plate(&FLAT, true).as_bytes()).unwrap();
    let m = read_step(placed_plates().as_bytes()).unwrap();
    assert_eq!(m.faces.len(), 2);
    assert_eq!(m.shells.len(), 2);
    let unit = m.length_unit.as_ref().unwrap();
    assert_eq!((unit.name.as_str(), unit.millimetres), ("MILLIMETRE", 1.0));
    // The two placements, written out: (x, y, z) -> (x + 10, y, z) and -> (0, 5 + x, y) (the
    // frame's x is the world y, its y = z x x the world z).
    let places: [fn(Point3) -> Point3; 2] = [
        |p| Point3::new(p.x + 10.0, p.y, p.z),
        |p| Point3::new(p.z, 5.0 + p.x, p.y),
    ];
    let s0 = part.faces[0].surface.as_ref().unwrap();
    for (f, place) in m.faces.iter().zip(places) {
        assert_eq!(f.entity, "#99");
        assert_eq!(
            f.loops.as_ref().unwrap(),
            part.faces[0].loops.as_ref().unwrap()
        );
        let s = f.surface.as_ref().unwrap();
        for uv in [[0.0, 0.0], [3.0, -1.0], [10.0, 10.0]] {
            assert!(s.point(uv).distance(place(s0.point(uv))) < 1e-14, "{uv:?}");
        }
        for (e, e0) in f
            .edges
            .iter()
            .flatten()
            .zip(part.faces[0].edges.iter().flatten())
        {
            assert_eq!(e.range, e0.range);
            let (a, b) = e.ends();
            let (a0, b0) = e0.ends();
            assert!(a.distance(place(a0)) < 1e-14 && b.distance(place(b0)) < 1e-14);
        }
        assert!(surface_to_edges(f).unwrap() < 1e-14);
    }
}

/// A file's topology: its name, the faces of each solid's shells, its free shells (faces,
/// closed), and how many of its faces `OpenCASCADE` lists `REVERSED` (their outward normal
/// against the surface's `S_u x S_v`).
type Topology = (&'static str, Vec<Vec<usize>>, Vec<(usize, bool)>, usize);

#[test]
fn a_part_in_another_length_unit_is_placed_in_the_assembly_s() {
    // The assembly in metres, the plate in millimetres: each occurrence scales the plate by
    // 1/1000 before placing it; the model is in metres.
    let text = placed_plates()
        .replace(
            "#8006=SHAPE_REPRESENTATION('',(#8010,#8011,#8012),#9010);",
            "#8006=SHAPE_REPRESENTATION('',(#8010,#8011,#8012),#8100);
#8100=(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNIT_ASSIGNED_CONTEXT((#8101,#9012,#9013))REPRESENTATION_CONTEXT('',''));
#8101=(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT($,.METRE.));",
        );
    let m = read_step(text.as_bytes()).unwrap();
    let unit = m.length_unit.as_ref().unwrap();
    assert_eq!((unit.name.as_str(), unit.millimetres), ("METRE", 1000.0));
    let part = read_step(plate(&FLAT, true).as_bytes()).unwrap();
    let s0 = part.faces[0].surface.as_ref().unwrap();
    let places: [fn(Point3) -> Point3; 2] = [
        |p| Point3::new(p.x * 1e-3 + 10.0, p.y * 1e-3, p.z * 1e-3),
        |p| Point3::new(p.z * 1e-3, 5.0 + p.x * 1e-3, p.y * 1e-3),
    ];
    for (f, place) in m.faces.iter().zip(places) {
        assert_eq!(
            f.loops.as_ref().unwrap(),
            part.faces[0].loops.as_ref().unwrap()
        );
        let s = f.surface.as_ref().unwrap();
        for uv in [[0.0, 0.0], [3.0, -1.0], [10.0, 10.0]] {
            assert!(s.point(uv).distance(place(s0.point(uv))) < 1e-15, "{uv:?}");
        }
        assert!(surface_to_edges(f).unwrap() < 1e-14);
    }
}

#[test]
fn solids_and_shells_of_the_real_files_are_opencascade_s() {
    // From `OpenCASCADE`'s explorers on the same files (OCP 8.0).
    let one = |n: usize| vec![vec![n]];
    let cases: Vec<Topology> = vec![
        ("0603_SMD.stp", one(90), vec![], 11),
        (
            "I22_2_5_16withEPL22_6_16.stp",
            vec![vec![36], vec![36]],
            vec![],
            12,
        ),
        (
            "RLF_12545.stp",
            vec![vec![10], vec![27], vec![10]],
            vec![],
            20,
        ),
        ("SOT23.stp", vec![], vec![(1, false); 73], 0),
        ("SOD_323.stp", vec![], vec![(1, false); 75], 0),
        (
            "SOT404.stp",
            vec![vec![25], vec![3], vec![6], vec![24]],
            vec![(17, false)],
            22,
        ),
        ("TSM_103_01_L_DV_A.stp", vec![vec![418, 8, 8]], vec![], 193),
        ("TSM_104_01_L_DV_A.stp", vec![vec![536, 8, 8]], vec![], 252),
    ];
    for (file, solids, free, reversed) in cases {
        let path = format!("{IDF}/{file}");
        let Some(text) = rs_testkit::system_file(&path, "freecad") else {
            return;
        };
        let m = read_step(&text).unwrap();
        let got: Vec<Vec<usize>> = m
            .solids
            .iter()
            .map(|s| s.shells.iter().map(|&k| m.shells[k].faces.len()).collect())
            .collect();
        assert_eq!(got, solids, "{file}");
        let in_solids: Vec<usize> = m.solids.iter().flat_map(|s| s.shells.clone()).collect();
        let got_free: Vec<(usize, bool)> = (0..m.shells.len())
            .filter(|k| !in_solids.contains(k))
            .map(|k| (m.shells[k].faces.len(), m.shells[k].closed))
            .collect();
        assert_eq!(got_free, free, "{file}");
        // Solids' shells, then free shells: the faces in order, each once.
        let order: Vec<usize> = in_solids
            .iter()
            .chain(
                (0..m.shells.len())
                    .filter(|k| !in_solids.contains(k))
                    .collect::<Vec<_>>()
                    .iter(),
            )
            .flat_map(|&k| m.shells[k].faces.clone())
            .collect();
        assert_eq!(order, (0..m.faces.len()).collect::<Vec<_>>(), "{file}");
        assert_eq!(
            m.length_unit.as_ref().map(|u| u.millimetres),
            Some(1.0),
            "{file}"
        );
        let got = m.faces.iter().filter(|f| !f.same_sense).count();
        assert_eq!(
            got, reversed,
            "{file}: faces against their surface's normal"
        );
    }
}

/// The bounding box centre of the placed edges of faces `range`.
fn edges_centre(m: &CadModel, range: std::ops::Range<usize>) -> Point3 {
    let mut lo = Point3::new(f64::INFINITY, f64::INFINITY, f64::INFINITY);
    let mut hi = lo * -1.0;
    for f in &m.faces[range] {
        for e in f.edges.iter().flatten() {
            for p in e.sample(33) {
                lo = Point3::new(lo.x.min(p.x), lo.y.min(p.y), lo.z.min(p.z));
                hi = Point3::new(hi.x.max(p.x), hi.y.max(p.y), hi.z.max(p.z));
            }
        }
    }
    (lo + hi) * 0.5
}

#[test]
fn as1_occurrences_are_placed_as_the_file_s_validation_centroids_say() {
    let Some(text) = gmsh_demo("demos/api/as1-tu-203.stp.gz") else {
        return;
    };
    let m = read_step(&text).unwrap();
    let sizes: Vec<usize> = m
        .solids
        .iter()
        .map(|s| m.shells[s.shells[0]].faces.len())
        .collect();
    assert_eq!(
        sizes,
        [8, 8, 4, 7, 8, 7, 8, 7, 8, 16, 18, 7, 8, 7, 8, 7, 8, 16]
    );
    assert_eq!(m.faces.len(), 160);
    // The file's own validation properties ('centroid of instance - ...', in the assembly's
    // coordinates): the rod assembly (two nuts and a rod, symmetric about its centre) at
    // (90, 75, 60), the plate at (90, 75, 10). A centrally symmetric part's centroid is the
    // centre of its edges' box, wherever it is turned.
    let rod_assembly = edges_centre(&m, 0..20);
    assert!(
        rod_assembly.distance(Point3::new(90.0, 75.0, 60.0)) < 1e-9,
        "{rod_assembly:?}"
    );
    let plate = edges_centre(&m, 81..99);
    assert!(
        plate.distance(Point3::new(90.0, 75.0, 10.0)) < 1e-6,
        "{plate:?}"
    );
    // The two nuts of the rod assembly sit 173 apart (at z = 186.5 and 13.5 along the rod).
    let (n1, n2) = (edges_centre(&m, 0..8), edges_centre(&m, 8..16));
    assert!((n1.distance(n2) - 173.0).abs() < 1e-9, "{n1:?} {n2:?}");
    // Every nut occurrence is the same nut moved rigidly: its edges' chords are the first's.
    let chords = |k: usize| -> Vec<f64> {
        m.faces[k..k + 8]
            .iter()
            .flat_map(|f| f.edges.iter().flatten())
            .map(|e| {
                let (a, b) = e.ends();
                a.distance(b)
            })
            .collect()
    };
    let first = chords(0);
    for (k, f) in m.faces.iter().enumerate() {
        if k > 0 && f.entity == m.faces[0].entity {
            for (a, b) in chords(k).iter().zip(&first) {
                assert!((a - b).abs() < 1e-9, "nut at face {k}");
            }
        }
    }
}

/// A whole torus (R = 3, r = 1 about z) as `OpenCASCADE` writes it: one vertex at (4, 0, 0),
/// two seam edges (the outer equator, pcurves `v = 2 pi` then `v = 0`; the meridian at
/// `u = 0`, pcurves `u = 2 pi` then `u = 0`), the loop `(-e1, -e2, +e1, +e2)`.
fn whole_torus() -> String {
    let tau = std::f64::consts::TAU;
    let mut b = Builder::new();
    let ax = b.axis3([0.0; 3], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
    let torus = b.add(&format!("TOROIDAL_SURFACE('',#{ax},3.,1.)"));
    let v = b.vertex([4.0, 0.0, 0.0]);
    let seam = |b: &mut Builder, c3: u64, p: [[f64; 2]; 2], d: [f64; 2]| {
        let (l1, l2) = (b.line(&p[0], &d), b.line(&p[1], &d));
        let (p1, p2) = (b.pcurve(torus, l1), b.pcurve(torus, l2));
        let s = b.add(&format!("SEAM_CURVE('',#{c3},(#{p1},#{p2}),.PCURVE_S1.)"));
        b.edge(v, v, s, true)
    };
    let equator = b.add(&format!("CIRCLE('',#{ax},4.)"));
    let e1 = seam(&mut b, equator, [[0.0, tau], [0.0, 0.0]], [1.0, 0.0]);
    let max = b.axis3([3.0, 0.0, 0.0], [0.0, -1.0, 0.0], [1.0, 0.0, 0.0]);
    let meridian = b.add(&format!("CIRCLE('',#{max},1.)"));
    let e2 = seam(&mut b, meridian, [[tau, 0.0], [0.0, 0.0]], [0.0, 1.0]);
    let uses = [
        b.oriented(e1, false),
        b.oriented(e2, false),
        b.oriented(e1, true),
        b.oriented(e2, true),
    ];
    let bo = b.bound(&uses, true, true);
    b.file(&[bo], torus)
}

#[test]
fn a_whole_torus_of_four_seam_uses_is_its_rectangle() {
    let tau = std::f64::consts::TAU;
    let m = read_step(whole_torus().as_bytes()).unwrap();
    let f = &m.faces[0];
    assert!(!f.natural_bounds);
    let loops = closed(f.loops.clone().unwrap());
    assert_eq!(loops.len(), 1);
    assert_eq!(loops[0].len(), 4);
    assert!((loop_area(&loops[0]) - tau * tau).abs() < 1e-12);
    let b = f.loops_box().unwrap();
    assert!(b.min.x.abs() < 1e-15 && b.min.y.abs() < 1e-15);
    assert!((b.max.x - tau).abs() < 1e-15 && (b.max.y - tau).abs() < 1e-15);
    assert!(surface_to_edges(f).unwrap() < 1e-14);
}

/// A band of the unit cylinder about z across its seam, `-1 <= u <= 1`, `0 <= v <= 1`, its
/// bottom pcurve written a period up (`u = 2 pi + t`), the others at the 3-D angles.
#[test]
fn a_loop_through_the_seam_is_made_continuous_and_moved_into_the_base_period() {
    let tau = std::f64::consts::TAU;
    let mut b = Builder::new();
    let ax = b.axis3([0.0; 3], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
    let cyl = b.add(&format!("CYLINDRICAL_SURFACE('',#{ax},1.)"));
    let at = |u: f64, v: f64| [u.cos(), u.sin(), v];
    let (va, vb, vc, vd) = (
        b.vertex(at(-1.0, 0.0)),
        b.vertex(at(1.0, 0.0)),
        b.vertex(at(1.0, 1.0)),
        b.vertex(at(-1.0, 1.0)),
    );
    let arc = |b: &mut Builder, z: f64, u0: f64, s: u64, e: u64| {
        let a = b.axis3([0.0, 0.0, z], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
        let c3 = b.add(&format!("CIRCLE('',#{a},1.)"));
        let l2 = b.line(&[u0, z], &[1.0, 0.0]);
        let pc = b.pcurve(cyl, l2);
        let sc = b.add(&format!("SURFACE_CURVE('',#{c3},(#{pc}),.PCURVE_S1.)"));
        b.edge(s, e, sc, true)
    };
    let side = |b: &mut Builder, u: f64, s: u64, e: u64| {
        let l3 = b.line(&at(u, 0.0), &[0.0, 0.0, 1.0]);
        let l2 = b.line(&[u, 0.0], &[0.0, 1.0]);
        let pc = b.pcurve(cyl, l2);
        let sc = b.add(&format!("SURFACE_CURVE('',#{l3},(#{pc}),.PCURVE_S1.)"));
        b.edge(s, e, sc, true)
    };
    let bottom = arc(&mut b, 0.0, tau, va, vb);
    let right = side(&mut b, 1.0, vb, vc);
    let top = arc(&mut b, 1.0, 0.0, vd, vc);
    let left = side(&mut b, -1.0, va, vd);
    let uses = [
        b.oriented(bottom, true),
        b.oriented(right, true),
        b.oriented(top, false),
        b.oriented(left, false),
    ];
    let bo = b.bound(&uses, true, true);
    let m = read_step(b.file(&[bo], cyl).as_bytes()).unwrap();
    let f = &m.faces[0];
    let loops = closed(f.loops.clone().unwrap());
    assert!((loop_area(&loops[0]) - 2.0).abs() < 1e-12);
    let bx = f.loops_box().unwrap();
    assert!(
        (bx.min.x + 1.0).abs() < 1e-12 && (bx.max.x - 1.0).abs() < 1e-12,
        "{bx:?}"
    );
    assert!(surface_to_edges(f).unwrap() < 1e-14);
}
