//! The faces, shells and solids of a file in `OpenCASCADE`'s explorer order (see the module
//! docs of [`super`] for the rule), each face use with the assembly placement of its
//! occurrence and its orientation in its shell.

use std::collections::{HashMap, HashSet};

use rs_geom::Affine3;
use rs_geom::brep::{Shell, Solid};

use super::error::{Result, StepError};
use super::geometry;
use super::graph::{Attrs, Graph, Instance, Value};
use super::units;

/// The deepest nesting of products, representations and topology followed.
const MAX_DEPTH: usize = 64;

/// The most face uses listed (a face used by many assembly occurrences counts each time), so a
/// tree of assemblies that doubles at every level cannot run away.
pub(crate) const MAX_FACE_USES: usize = 1 << 20;

/// One use of a face: the face, the representation context it is read in, the context whose
/// length unit its placed coordinates are in (its own, or the top assembly's), the placement
/// of its assembly occurrence (`None`: where the file puts it) and whether its shell or an
/// `ORIENTED_FACE` reverses it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct FaceUse {
    pub(crate) face: u64,
    pub(crate) context: Option<u64>,
    pub(crate) unit_context: Option<u64>,
    pub(crate) placement: Option<Affine3>,
    pub(crate) reversed: bool,
}

/// One use of a shell: its entity, its faces (indices into the face uses), whether the file
/// calls it closed (a `CLOSED_SHELL`) and whether it is (no edge used by only one face).
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct ShellUse {
    pub(crate) entity: u64,
    pub(crate) faces: Vec<usize>,
    pub(crate) closed_claim: bool,
    pub(crate) free_edges: bool,
}

impl ShellUse {
    /// Closed in the file and in fact: a `CLOSED_SHELL` every edge of which two faces use.
    pub(crate) fn closed(&self) -> bool {
        self.closed_claim && !self.free_edges
    }

    /// The model's shell: named `#entity`, closed as [`ShellUse::closed`] says.
    pub(crate) fn to_shell(&self) -> Shell {
        Shell {
            entity: format!("#{}", self.entity),
            faces: self.faces.clone(),
            closed: self.closed(),
        }
    }
}

/// One use of a solid: its entity and its shells (the outer one, then the voids), indices
/// into the shell uses.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct SolidUse {
    pub(crate) entity: u64,
    pub(crate) shells: Vec<usize>,
}

impl SolidUse {
    /// The model's solid, named `#entity`.
    pub(crate) fn to_solid(&self) -> Solid {
        Solid {
            entity: format!("#{}", self.entity),
            shells: self.shells.clone(),
        }
    }
}

/// The topology of a file in explorer order.
#[derive(Clone, Debug, Default)]
pub(crate) struct Structure {
    pub(crate) faces: Vec<FaceUse>,
    pub(crate) shells: Vec<ShellUse>,
    pub(crate) solids: Vec<SolidUse>,
}

/// The indexes of the product structure, built in one pass in file order.
#[derive(Default)]
struct Index {
    /// Relating product definition -> its `NEXT_ASSEMBLY_USAGE_OCCURRENCE`s and their related
    /// product definitions, in file order.
    children: HashMap<u64, Vec<(u64, u64)>>,
    /// Product definitions used as components.
    used: HashSet<u64>,
    /// Product definition (or occurrence) -> its `PRODUCT_DEFINITION_SHAPE`s.
    shapes: HashMap<u64, Vec<u64>>,
    /// `PRODUCT_DEFINITION_SHAPE` -> the representations of its `SHAPE_DEFINITION_REPRESENTATION`s.
    reps: HashMap<u64, Vec<u64>>,
    /// `PRODUCT_DEFINITION_SHAPE` of an occurrence -> the representation relationship of its
    /// `CONTEXT_DEPENDENT_SHAPE_REPRESENTATION`.
    placements: HashMap<u64, u64>,
    /// Representation -> the representations it is related to by a
    /// `SHAPE_REPRESENTATION_RELATIONSHIP` without a transformation (either side).
    related: HashMap<u64, Vec<u64>>,
}

struct Walk<'a> {
    g: &'a Graph,
    ix: Index,
    out: Structure,
    /// Labels on the current path (cycle guard).
    path: Vec<u64>,
}

/// The face, shell and solid uses of the file in order.
pub(crate) fn structure(g: &Graph) -> Result<Structure> {
    let mut w = Walk {
        g,
        ix: index(g),
        out: Structure::default(),
        path: Vec::new(),
    };
    let roots: Vec<u64> = g
        .instances()
        .iter()
        .filter(|i| is_product_definition(i) && !w.ix.used.contains(&i.label))
        .map(|i| i.label)
        .collect();
    for r in roots {
        w.product(r, 0, Affine3::IDENTITY, None)?;
    }
    if w.out.faces.is_empty() {
        // No product structure leads to faces: every shape representation in file order, then
        // every solid or surface model, then every shell.
        w.out = Structure::default();
        let levels: [&dyn Fn(&Instance) -> bool; 3] = [
            &|i: &Instance| {
                i.parts
                    .iter()
                    .any(|p| p.name.ends_with("SHAPE_REPRESENTATION"))
            },
            &|i: &Instance| {
                i.is("MANIFOLD_SOLID_BREP")
                    || i.is("BREP_WITH_VOIDS")
                    || i.is("SHELL_BASED_SURFACE_MODEL")
            },
            &|i: &Instance| i.is("CLOSED_SHELL") || i.is("OPEN_SHELL"),
        ];
        for (level, pick) in levels.iter().enumerate() {
            let labels: Vec<u64> = g
                .instances()
                .iter()
                .filter(|i| pick(i))
                .map(|i| i.label)
                .collect();
            for l in labels {
                let at = Site {
                    context: None,
                    unit_context: None,
                    placement: Affine3::IDENTITY,
                };
                if level == 0 {
                    w.representation(l, 0, at)?;
                } else {
                    w.item(l, at, 0)?;
                }
            }
            if !w.out.faces.is_empty() {
                break;
            }
        }
    }
    Ok(w.out)
}

fn is_product_definition(i: &Instance) -> bool {
    i.parts.iter().any(|p| {
        p.name == "PRODUCT_DEFINITION" || p.name == "PRODUCT_DEFINITION_WITH_ASSOCIATED_DOCUMENTS"
    })
}

fn index(g: &Graph) -> Index {
    let mut ix = Index::default();
    for i in g.instances() {
        let Some(p) = i.parts.first() else { continue };
        let r = |k: usize| match p.params.get(k) {
            Some(Value::Ref(r)) => Some(*r),
            _ => None,
        };
        if i.parts.len() == 1 {
            match p.name.as_str() {
                "NEXT_ASSEMBLY_USAGE_OCCURRENCE" => {
                    if let (Some(a), Some(b)) = (r(3), r(4)) {
                        ix.children.entry(a).or_default().push((i.label, b));
                        ix.used.insert(b);
                    }
                }
                "PRODUCT_DEFINITION_SHAPE" => {
                    if let Some(d) = r(2) {
                        ix.shapes.entry(d).or_default().push(i.label);
                    }
                }
                "SHAPE_DEFINITION_REPRESENTATION" => {
                    if let (Some(d), Some(rep)) = (r(0), r(1)) {
                        ix.reps.entry(d).or_default().push(rep);
                    }
                }
                "CONTEXT_DEPENDENT_SHAPE_REPRESENTATION" => {
                    if let (Some(rel), Some(pds)) = (r(0), r(1)) {
                        ix.placements.entry(pds).or_insert(rel);
                    }
                }
                "SHAPE_REPRESENTATION_RELATIONSHIP" => {
                    if let (Some(a), Some(b)) = (r(2), r(3)) {
                        ix.related.entry(a).or_default().push(b);
                        ix.related.entry(b).or_default().push(a);
                    }
                }
                _ => {}
            }
        } else if i.is("SHAPE_REPRESENTATION_RELATIONSHIP")
            && !i.is("REPRESENTATION_RELATIONSHIP_WITH_TRANSFORMATION")
            && let Ok(rr) = i.record("REPRESENTATION_RELATIONSHIP")
            && let (Ok(a), Ok(b)) = (rr.reference(2, "rep_1"), rr.reference(3, "rep_2"))
        {
            ix.related.entry(a).or_default().push(b);
            ix.related.entry(b).or_default().push(a);
        }
    }
    ix
}

/// Where items are being read: their representation's context, the context of the top
/// assembly whose coordinates the occurrence's placement gives (`None` outside assemblies) and
/// that placement.
#[derive(Clone, Copy)]
struct Site {
    context: Option<u64>,
    unit_context: Option<u64>,
    placement: Affine3,
}

impl Walk<'_> {
    fn enter(&mut self, label: u64, depth: usize) -> Result<bool> {
        if depth > MAX_DEPTH {
            return Err(StepError::TooDeep {
                what: format!("#{label}"),
                limit: MAX_DEPTH,
            });
        }
        if self.path.contains(&label) {
            return Ok(false);
        }
        self.path.push(label);
        Ok(true)
    }

    /// A product definition: its own shape representations, then its components
    /// (`NEXT_ASSEMBLY_USAGE_OCCURRENCE`s in file order), each as often as it is used and
    /// placed by its occurrence's transformation after `placement` (into the coordinates and
    /// length unit of the top assembly's representation context `unit_context`).
    fn product(
        &mut self,
        pd: u64,
        depth: usize,
        placement: Affine3,
        unit_context: Option<u64>,
    ) -> Result<()> {
        if !self.enter(pd, depth)? {
            return Err(StepError::AssemblyCycle {
                what: format!("#{pd}"),
            });
        }
        let reps: Vec<u64> = self
            .ix
            .shapes
            .get(&pd)
            .into_iter()
            .flatten()
            .flat_map(|s| self.ix.reps.get(s).into_iter().flatten())
            .copied()
            .collect();
        for rep in reps {
            let at = Site {
                context: None,
                unit_context,
                placement,
            };
            self.representation(rep, depth + 1, at)?;
        }
        let children = self.ix.children.get(&pd).cloned().unwrap_or_default();
        for (nauo, c) in children {
            let (t, parent_context) = self.occurrence_placement(nauo)?;
            self.product(
                c,
                depth + 1,
                placement.after(t),
                unit_context.or(parent_context),
            )?;
        }
        self.path.pop();
        Ok(())
    }

    /// The placement of an occurrence (child coordinates to parent coordinates) and the
    /// parent representation's context: `A(item_2) k A(item_1)^-1` of the
    /// `ITEM_DEFINED_TRANSFORMATION` of the representation relationship of the occurrence's
    /// `CONTEXT_DEPENDENT_SHAPE_REPRESENTATION` (`A(p)` the map from placement `p`'s frame to
    /// its representation's coordinates, `k` the child's length unit in the parent's, 1 when
    /// they agree); the identity for an occurrence the file does not place.
    fn occurrence_placement(&self, nauo: u64) -> Result<(Affine3, Option<u64>)> {
        let Some(rel) = self
            .ix
            .shapes
            .get(&nauo)
            .into_iter()
            .flatten()
            .find_map(|pds| self.ix.placements.get(pds))
        else {
            return Ok((Affine3::IDENTITY, None));
        };
        let ri = self.g.get(*rel, &format!("#{nauo}"))?;
        let Ok(rt) = ri.record("REPRESENTATION_RELATIONSHIP_WITH_TRANSFORMATION") else {
            return Ok((Affine3::IDENTITY, None));
        };
        let ti = self
            .g
            .get(rt.reference(0, "transformation_operator")?, &ri.what())?;
        let Ok(t) = ti.record("ITEM_DEFINED_TRANSFORMATION") else {
            return Err(StepError::Unsupported {
                what: ti.what(),
                role: "transformation",
                name: ti.type_name(),
            });
        };
        let from = geometry::placement(self.g, t.reference(2, "transform_item_1")?, &ti.what())?;
        let to = geometry::placement(self.g, t.reference(3, "transform_item_2")?, &ti.what())?;
        // The contexts of the child (rep_1) and parent (rep_2) representations.
        let context = |i: usize, name: &'static str| -> Option<u64> {
            let rep = ri
                .record("REPRESENTATION_RELATIONSHIP")
                .ok()?
                .reference(i, name)
                .ok()?;
            let r = self.g.get(rep, "").ok()?;
            let rec = r
                .parts
                .iter()
                .find(|p| p.name.ends_with("REPRESENTATION"))?;
            Attrs { inst: r, part: rec }
                .reference(2, "context_of_items")
                .ok()
        };
        let (child, parent) = (context(2, "rep_1"), context(3, "rep_2"));
        let mm = |c: Option<u64>| {
            c.and_then(|c| units::context_units(self.g, c).ok())
                .map_or(1.0, |u| u.mm_per_length)
        };
        let k = mm(child) / mm(parent);
        let t = if k == 1.0 || !k.is_finite() || k <= 0.0 {
            Affine3::between(&from, &to)
        } else {
            Affine3::from_frame(&to)
                .after(uniform_scale(k))
                .after(Affine3::from_frame(&from).rigid_inverse())
        };
        Ok((t, parent))
    }

    /// A representation: its items in order, then the representations related to it without
    /// a transformation (not those already on the path: the relation is symmetric).
    fn representation(&mut self, rep: u64, depth: usize, at: Site) -> Result<()> {
        if !self.enter(rep, depth)? {
            return Err(StepError::Cycle {
                what: format!("#{rep}: the representation contains itself"),
            });
        }
        let inst = self.g.get(rep, "a shape definition")?;
        let rec = inst
            .parts
            .iter()
            .find(|p| p.name.ends_with("REPRESENTATION"))
            .ok_or_else(|| StepError::WrongType {
                what: inst.what(),
                expected: "representation".into(),
            })?;
        let attrs = Attrs { inst, part: rec };
        let items = attrs.refs(1, "items")?;
        let at = Site {
            context: attrs.reference(2, "context_of_items").ok(),
            unit_context: at.unit_context,
            placement: at.placement,
        };
        for it in items {
            self.item(it, at, depth + 1)?;
        }
        let related = self.ix.related.get(&rep).cloned().unwrap_or_default();
        for r in related {
            if !self.path.contains(&r) {
                self.representation(r, depth + 1, at)?;
            }
        }
        self.path.pop();
        Ok(())
    }

    /// A representation item: solids, surface models, shells, faces, mapped items.
    fn item(&mut self, label: u64, at: Site, depth: usize) -> Result<()> {
        let inst = self.g.get(label, "a representation")?;
        let what = inst.what();
        let name = inst.first_name();
        if inst.is("ADVANCED_FACE")
            || inst.is("FACE_SURFACE")
            || (name == "ORIENTED_FACE" && !inst.is_complex())
        {
            return self.face(label, at, false, depth);
        }
        match (inst.is_complex(), name) {
            (false, "MANIFOLD_SOLID_BREP" | "FACETED_BREP") => {
                let outer = inst.simple()?.reference(1, "outer")?;
                self.solid(label, &[outer], at, depth)
            }
            (false, "BREP_WITH_VOIDS") => {
                let a = inst.simple()?;
                let mut shells = vec![a.reference(1, "outer")?];
                shells.extend(a.refs(2, "voids")?);
                self.solid(label, &shells, at, depth)
            }
            (false, "SHELL_BASED_SURFACE_MODEL") => {
                let shells = inst.simple()?.refs(1, "sbsm_boundary")?;
                if !self.enter(label, depth)? {
                    return Err(StepError::Cycle { what });
                }
                for s in shells {
                    self.shell(s, at, false, depth + 1)?;
                }
                self.path.pop();
                Ok(())
            }
            (
                false,
                "CLOSED_SHELL" | "OPEN_SHELL" | "ORIENTED_CLOSED_SHELL" | "ORIENTED_OPEN_SHELL",
            ) => self.shell(label, at, false, depth).map(|_| ()),
            (false, "MAPPED_ITEM") => {
                let map = self
                    .g
                    .get(inst.simple()?.reference(1, "mapping_source")?, &what)?;
                let rep = map
                    .record("REPRESENTATION_MAP")?
                    .reference(1, "mapped_representation")?;
                self.representation(rep, depth + 1, at)
            }
            _ => Ok(()),
        }
    }

    /// A face use (an `ORIENTED_FACE` followed to its face, reversing it when `.F.`).
    fn face(&mut self, label: u64, at: Site, reversed: bool, depth: usize) -> Result<()> {
        let inst = self.g.get(label, "a shell")?;
        if inst.is("ADVANCED_FACE") || inst.is("FACE_SURFACE") {
            if self.out.faces.len() >= MAX_FACE_USES {
                return Err(StepError::TooMany {
                    what: "face uses".into(),
                    limit: MAX_FACE_USES,
                });
            }
            self.out.faces.push(FaceUse {
                face: label,
                context: at.context,
                unit_context: at.unit_context.or(at.context),
                placement: (!at.placement.is_identity()).then_some(at.placement),
                reversed,
            });
            return Ok(());
        }
        if inst.is("ORIENTED_FACE") && !inst.is_complex() {
            let a = inst.simple()?;
            let element = a.reference(2, "face_element")?;
            let forward = a.boolean(3, "orientation")?;
            if !self.enter(label, depth)? {
                return Err(StepError::Cycle { what: inst.what() });
            }
            self.face(element, at, reversed ^ !forward, depth + 1)?;
            self.path.pop();
            return Ok(());
        }
        // Anything else in a face list is read as an item (a mapped item, a shell).
        self.item(label, at, depth + 1)
    }

    /// A shell use (an `ORIENTED_*_SHELL` followed to its shell, reversing it when `.F.`): its
    /// faces in order; the index of the new shell, `None` for an item that is not a shell.
    fn shell(
        &mut self,
        label: u64,
        at: Site,
        reversed: bool,
        depth: usize,
    ) -> Result<Option<usize>> {
        let inst = self.g.get(label, "a solid")?;
        let what = inst.what();
        let name = inst.first_name();
        if !self.enter(label, depth)? {
            return Err(StepError::Cycle { what });
        }
        let out = match (inst.is_complex(), name) {
            (false, "ORIENTED_CLOSED_SHELL" | "ORIENTED_OPEN_SHELL") => {
                let a = inst.simple()?;
                let element = a.reference(2, "element")?;
                let forward = a.boolean(3, "orientation")?;
                self.shell(element, at, reversed ^ !forward, depth + 1)?
            }
            (false, "CLOSED_SHELL" | "OPEN_SHELL") => {
                let faces = inst.simple()?.refs(1, "cfs_faces")?;
                let first = self.out.faces.len();
                for f in &faces {
                    self.face(*f, at, reversed, depth + 1)?;
                }
                let free_edges = name == "CLOSED_SHELL" && has_free_edges(self.g, &faces);
                self.out.shells.push(ShellUse {
                    entity: label,
                    faces: (first..self.out.faces.len()).collect(),
                    closed_claim: name == "CLOSED_SHELL",
                    free_edges,
                });
                Some(self.out.shells.len() - 1)
            }
            _ => None,
        };
        self.path.pop();
        Ok(out)
    }

    /// A solid of an outer shell and voids; a solid whose outer shell is not closed (an
    /// `OPEN_SHELL`, or a `CLOSED_SHELL` with free edges) is no solid for `OpenCASCADE`: its
    /// shells stay free shells.
    fn solid(&mut self, label: u64, shells: &[u64], at: Site, depth: usize) -> Result<()> {
        if !self.enter(label, depth)? {
            return Err(StepError::Cycle {
                what: format!("#{label}"),
            });
        }
        let mut uses = Vec::new();
        for &s in shells {
            uses.extend(self.shell(s, at, false, depth + 1)?);
        }
        self.path.pop();
        if let Some(&outer) = uses.first()
            && self.out.shells[outer].closed()
        {
            self.out.solids.push(SolidUse {
                entity: label,
                shells: uses,
            });
        }
        Ok(())
    }
}

/// The map `p -> k p`.
pub(crate) fn uniform_scale(k: f64) -> Affine3 {
    Affine3 {
        m: [[k, 0.0, 0.0, 0.0], [0.0, k, 0.0, 0.0], [0.0, 0.0, k, 0.0]],
    }
}

/// Whether some edge of the faces (an `EDGE_CURVE` of their edge loops) is used by only one
/// of them, once: the shell has a gap there. Faces or loops that cannot be followed count no
/// edges (their own errors are reported with the face).
fn has_free_edges(g: &Graph, faces: &[u64]) -> bool {
    let mut uses: HashMap<u64, usize> = HashMap::new();
    for &f in faces {
        let mut face = f;
        // Through oriented faces to the face (chains are checked when the faces are listed).
        for _ in 0..MAX_DEPTH {
            match g.get(face, "") {
                Ok(i) if i.is("ORIENTED_FACE") => match i.simple().and_then(|a| a.reference(2, ""))
                {
                    Ok(next) => face = next,
                    Err(_) => break,
                },
                _ => break,
            }
        }
        let Ok(fi) = g.get(face, "") else { continue };
        let Ok(bounds) = fi.simple().and_then(|a| a.refs(1, "bounds")) else {
            continue;
        };
        for b in bounds {
            let Ok(edges) = g
                .get(b, "")
                .and_then(|bi| bi.simple()?.reference(1, "bound"))
                .and_then(|l| g.get(l, ""))
                .and_then(|li| {
                    if li.is("EDGE_LOOP") {
                        li.simple()?.refs(1, "edge_list")
                    } else {
                        Ok(Vec::new())
                    }
                })
            else {
                continue;
            };
            for e in edges {
                let Ok(ei) = g.get(e, "") else { continue };
                let edge = if ei.is("ORIENTED_EDGE") {
                    match ei.simple().and_then(|a| a.reference(3, "")) {
                        Ok(x) => x,
                        Err(_) => continue,
                    }
                } else {
                    e
                };
                *uses.entry(edge).or_default() += 1;
            }
        }
    }
    uses.values().any(|&n| n == 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two triangles sharing edge #22 (the third edges #23, #24 of each face its own), and a
    /// triangle whose edges are all its own.
    fn graph() -> Graph {
        let text = "ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;
#1=ADVANCED_FACE('',(#2),#0,.T.);
#2=FACE_OUTER_BOUND('',#3,.T.);
#3=EDGE_LOOP('',(#4,#5,#6));
#4=ORIENTED_EDGE('',*,*,#21,.T.);
#5=ORIENTED_EDGE('',*,*,#22,.T.);
#6=ORIENTED_EDGE('',*,*,#23,.T.);
#11=ADVANCED_FACE('',(#12),#0,.T.);
#12=FACE_BOUND('',#13,.T.);
#13=EDGE_LOOP('',(#14,#15,#16));
#14=ORIENTED_EDGE('',*,*,#21,.F.);
#15=ORIENTED_EDGE('',*,*,#22,.F.);
#16=ORIENTED_EDGE('',*,*,#23,.F.);
#31=ORIENTED_FACE('',*,#1,.F.);
ENDSEC;\nEND-ISO-10303-21;\n";
        Graph::parse(text.as_bytes()).unwrap()
    }

    #[test]
    fn free_edges_are_edges_used_once() {
        let g = graph();
        assert!(!has_free_edges(&g, &[1, 11]));
        assert!(!has_free_edges(&g, &[31, 11]));
        assert!(has_free_edges(&g, &[1]));
        // Unreadable faces count no edges.
        assert!(!has_free_edges(&g, &[1, 11, 77]));
    }
}
