//! Images of surfaces under affine maps, in the same parameters (the placements of assembly
//! components, IGES 124 matrices): see [`Surface::transformed`].

use rs_spline::Point3;

use super::{
    Cone, Cylinder, Extrusion, Offset, Plane, Reparam, Revolution, Sphere, Surface, Torus,
};
use crate::{Affine3, Frame, GeomError};

/// The largest relative deviation of a map's linear part `M` from a similarity (`M^T M = s^2
/// I`) accepted for surfaces that need one, and the largest deviation of its scale `s` from 1
/// that counts as no scaling: placements written with 10 or more significant digits pass, a
/// genuine shear or stretch does not.
const SIMILARITY_TOLERANCE: f64 = 1e-9;

/// A similarity's scale and whether it reverses orientation.
#[derive(Clone, Copy, Debug)]
struct Similarity {
    scale: f64,
    reflect: bool,
}

/// `m`'s linear part as a similarity, or its relative deviation from one.
fn similarity(m: &Affine3) -> Result<Similarity, f64> {
    let col = |j: usize| Point3::new(m.m[0][j], m.m[1][j], m.m[2][j]);
    let c = [col(0), col(1), col(2)];
    let s2 = (c[0].dot(c[0]) + c[1].dot(c[1]) + c[2].dot(c[2])) / 3.0;
    if !(s2 > 0.0 && s2.is_finite()) {
        return Err(f64::INFINITY);
    }
    let mut deviation = 0.0f64;
    for i in 0..3 {
        for j in i..3 {
            let target = if i == j { s2 } else { 0.0 };
            deviation = deviation.max((c[i].dot(c[j]) - target).abs() / s2);
        }
    }
    if deviation > SIMILARITY_TOLERANCE {
        return Err(deviation);
    }
    let s = s2.sqrt();
    Ok(Similarity {
        scale: if (s - 1.0).abs() <= SIMILARITY_TOLERANCE {
            1.0
        } else {
            s
        },
        reflect: m.determinant() < 0.0,
    })
}

/// The image of `surface` under `m` (see [`Surface::transformed`]).
pub(super) fn transformed(surface: &Surface, m: &Affine3) -> Result<Surface, GeomError> {
    if let Some(&value) = m.m.iter().flatten().find(|x| !x.is_finite()) {
        return Err(GeomError::NotFinite {
            what: "transformation matrix entry",
            value,
        });
    }
    let need = || {
        similarity(m).map_err(|deviation| GeomError::NotSimilarity {
            surface: surface.kind_name(),
            deviation,
        })
    };
    // A rotational surface's frame: x and z mapped; under a reflection y maps to -y', so the
    // angle runs backwards (u -> -u).
    let turned = |f: &Frame| {
        Frame::new(
            m.apply(f.origin),
            Some(m.apply_vector(f.z)),
            Some(m.apply_vector(f.x)),
        )
    };
    Ok(match surface {
        Surface::Plane(p) => {
            let sim = need()?;
            let f = p.frame();
            let (x, y) = (m.apply_vector(f.x), m.apply_vector(f.y));
            let frame = Frame::new(m.apply(f.origin), Some(x.cross(y)), Some(x))?;
            reparam(Surface::Plane(Plane::new(frame)), [sim.scale, sim.scale])?
        }
        Surface::Cylinder(c) => {
            let sim = need()?;
            let image = Cylinder::new(turned(c.frame())?, c.radius() * sim.scale)?;
            reparam(Surface::Cylinder(image), [angle_sign(sim), sim.scale])?
        }
        Surface::Cone(c) => {
            let sim = need()?;
            let image = Cone::new(turned(c.frame())?, c.radius() * sim.scale, c.semi_angle())?;
            reparam(Surface::Cone(image), [angle_sign(sim), sim.scale])?
        }
        Surface::Sphere(s) => {
            let sim = need()?;
            let image = Sphere::new(turned(s.frame())?, s.radius() * sim.scale)?;
            reparam(Surface::Sphere(image), [angle_sign(sim), 1.0])?
        }
        Surface::Torus(t) => {
            let sim = need()?;
            let image = Torus::new(
                turned(t.frame())?,
                t.major_radius() * sim.scale,
                t.minor_radius() * sim.scale,
            )?;
            reparam(Surface::Torus(image), [angle_sign(sim), 1.0])?
        }
        Surface::Revolution(r) => {
            // M R_d(u) = R_{det(Q) Q d}(u) M for M = s Q: a reflection reverses the axis.
            let sim = need()?;
            let axis = m.apply_vector(r.axis()) * angle_sign(sim);
            Surface::Revolution(Revolution::new(
                r.curve().map_affine(m)?,
                m.apply(r.axis_point()),
                axis,
            )?)
        }
        Surface::Extrusion(e) => Surface::Extrusion(Extrusion::new(
            e.curve().map_affine(m)?,
            m.apply_vector(e.vector()),
        )?),
        Surface::Offset(o) => {
            // The image's normal is det(Q) Q N: the distance scales and turns with it.
            let sim = need()?;
            Surface::Offset(Offset::new(
                transformed(o.base(), m)?,
                o.distance() * sim.scale * angle_sign(sim),
            )?)
        }
        Surface::BSpline(b) => Surface::BSpline(b.map_points(|p| m.apply(p))?),
        Surface::Reparam(r) => Surface::Reparam(Reparam::new(
            transformed(r.base(), m)?,
            r.swap(),
            r.scale(),
            r.offset(),
        )?),
    })
}

/// `-1` for a reflection, `1` otherwise.
fn angle_sign(sim: Similarity) -> f64 {
    if sim.reflect { -1.0 } else { 1.0 }
}

/// `s` in the parameters `(scale[0] u, scale[1] v)`, or `s` itself when both scales are 1.
fn reparam(s: Surface, scale: [f64; 2]) -> Result<Surface, GeomError> {
    if scale == [1.0, 1.0] {
        Ok(s)
    } else {
        Ok(Surface::Reparam(Reparam::new(s, false, scale, [0.0, 0.0])?))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::ParamSurface;
    use crate::surface::testing::{Rng, one_of_each};

    /// A random similarity: a rotation and translation, a scale, maybe a reflection.
    fn similarity_map(rng: &mut Rng, reflect: bool) -> Affine3 {
        let f = rng.frame(5.0);
        let s = rng.range(0.3, 3.0);
        let z = if reflect { -s } else { s };
        let scale = Affine3 {
            m: [[s, 0.0, 0.0, 0.0], [0.0, s, 0.0, 0.0], [0.0, 0.0, z, 0.0]],
        };
        Affine3::from_frame(&f).after(scale)
    }

    #[test]
    fn similarities_map_every_surface_exactly_in_the_same_parameters() {
        let mut rng = Rng::new(61);
        for k in 0..8 {
            let m = similarity_map(&mut rng, k % 2 == 1);
            let s = (m.determinant().abs()).cbrt();
            for surface in one_of_each(&mut rng) {
                let image = surface.transformed(&m).unwrap();
                for _ in 0..10 {
                    let uv = [rng.range(0.05, 0.95), rng.range(0.05, 0.95)];
                    let p = m.apply(surface.point(uv));
                    let q = image.point(uv);
                    assert!(
                        p.distance(q) < 1e-12 * 10.0 * s,
                        "{}: {p:?} vs {q:?}",
                        surface.kind_name()
                    );
                    // The normal follows: det(Q) Q n.
                    if let (Some(n), Some(n2)) = (surface.normal(uv), image.normal(uv)) {
                        let d = surface.derivatives(uv);
                        let expected = m
                            .apply_vector(d.du)
                            .cross(m.apply_vector(d.dv))
                            .normalized()
                            .unwrap();
                        assert!(n2.distance(expected) < 1e-10, "{}", surface.kind_name());
                        let _ = n;
                    }
                }
                assert_eq!(
                    image.poles().len(),
                    surface.poles().len(),
                    "{}",
                    surface.kind_name()
                );
                for (a, b) in image.periods().iter().zip(surface.periods()) {
                    assert_eq!(a.map(|p| (p * 1e9).round()), b.map(|p| (p * 1e9).round()));
                }
            }
        }
    }

    #[test]
    fn other_affine_maps_only_for_control_nets_and_extrusions() {
        let mut rng = Rng::new(62);
        let shear = Affine3 {
            m: [
                [1.0, 0.5, 0.0, 1.0],
                [0.0, 1.0, 0.0, 0.0],
                [0.0, 0.0, 2.0, 0.0],
            ],
        };
        for surface in one_of_each(&mut rng) {
            let image = surface.transformed(&shear);
            match surface {
                Surface::BSpline(ref b) => {
                    let image = image.unwrap();
                    let direct = b.map_points(|p| shear.apply(p)).unwrap();
                    assert_eq!(image, Surface::BSpline(direct));
                    let uv = [0.3, 0.6];
                    assert!(image.point(uv).distance(shear.apply(surface.point(uv))) < 1e-13);
                }
                Surface::Extrusion(_) => {
                    let uv = [0.3, 0.6];
                    assert!(
                        image
                            .unwrap()
                            .point(uv)
                            .distance(shear.apply(surface.point(uv)))
                            < 1e-13
                    );
                }
                _ => assert!(
                    matches!(image, Err(GeomError::NotSimilarity { .. })),
                    "{}",
                    surface.kind_name()
                ),
            }
        }
        let nan = Affine3 {
            m: [
                [f64::NAN, 0.0, 0.0, 0.0],
                [0.0, 1.0, 0.0, 0.0],
                [0.0, 0.0, 1.0, 0.0],
            ],
        };
        assert!(matches!(
            one_of_each(&mut rng)[0].transformed(&nan),
            Err(GeomError::NotFinite { .. })
        ));
        // A rigid motion keeps elementary surfaces of their kind.
        let rigid = Affine3::from_frame(&rng.frame(3.0));
        for surface in one_of_each(&mut rng).into_iter().take(5) {
            let image = surface.transformed(&rigid).unwrap();
            assert_eq!(image.kind_name(), surface.kind_name());
        }
    }
}
