//! The faces of a file in `OpenCASCADE`'s face-explorer order (see the module docs of
//! [`super`] for the rule).

use std::collections::HashMap;

use super::graph::{Graph, Instance};

/// The deepest nesting of products, representations and topology followed.
const MAX_DEPTH: usize = 64;

/// The most face uses listed (a face used by many assembly occurrences counts each time), so a
/// tree of assemblies that doubles at every level cannot run away.
pub(crate) const MAX_FACE_USES: usize = 1 << 20;

/// One use of a face: the face and the representation context it is read in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct FaceUse {
    pub(crate) face: u64,
    pub(crate) context: Option<u64>,
}

/// The indexes of the product structure, built in one pass in file order.
#[derive(Default)]
struct Index {
    /// Relating product definition -> the related ones of its `NEXT_ASSEMBLY_USAGE_OCCURRENCE`s.
    children: HashMap<u64, Vec<u64>>,
    /// Product definitions used as components.
    used: std::collections::HashSet<u64>,
    /// Product definition -> its `PRODUCT_DEFINITION_SHAPE`s.
    shapes: HashMap<u64, Vec<u64>>,
    /// `PRODUCT_DEFINITION_SHAPE` -> the representations of its `SHAPE_DEFINITION_REPRESENTATION`s.
    reps: HashMap<u64, Vec<u64>>,
    /// Representation -> the representations it is related to by a
    /// `SHAPE_REPRESENTATION_RELATIONSHIP` without a transformation (either side).
    related: HashMap<u64, Vec<u64>>,
}

struct Walk<'a> {
    g: &'a Graph,
    ix: Index,
    out: Vec<FaceUse>,
    /// Labels on the current path (cycle guard).
    path: Vec<u64>,
}

/// The face uses of the file in order.
pub(crate) fn face_order(g: &Graph) -> Result<Vec<FaceUse>, String> {
    let mut w = Walk {
        g,
        ix: index(g),
        out: Vec::new(),
        path: Vec::new(),
    };
    let roots: Vec<u64> = g
        .instances()
        .iter()
        .filter(|i| is_product_definition(i) && !w.ix.used.contains(&i.label))
        .map(|i| i.label)
        .collect();
    for r in roots {
        w.product(r, 0)?;
    }
    if w.out.is_empty() {
        // No product structure leads to faces: every shape representation in file order, then
        // every solid or surface model, then every shell.
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
                if level == 0 {
                    w.representation(l, 0)?;
                } else {
                    w.item(l, None, 0)?;
                }
            }
            if !w.out.is_empty() {
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
            Some(super::graph::Value::Ref(r)) => Some(*r),
            _ => None,
        };
        if i.parts.len() == 1 {
            match p.name.as_str() {
                "NEXT_ASSEMBLY_USAGE_OCCURRENCE" => {
                    if let (Some(a), Some(b)) = (r(3), r(4)) {
                        ix.children.entry(a).or_default().push(b);
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

impl Walk<'_> {
    fn enter(&mut self, label: u64, depth: usize) -> Result<bool, String> {
        if depth > MAX_DEPTH {
            return Err(format!(
                "#{label}: structure nested deeper than {MAX_DEPTH} levels"
            ));
        }
        if self.path.contains(&label) {
            return Ok(false);
        }
        self.path.push(label);
        Ok(true)
    }

    /// A product definition: its own shape representations, then its components
    /// (`NEXT_ASSEMBLY_USAGE_OCCURRENCE`s in file order), each as often as it is used.
    fn product(&mut self, pd: u64, depth: usize) -> Result<(), String> {
        if !self.enter(pd, depth)? {
            return Err(format!("#{pd}: the assembly contains itself"));
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
            self.representation(rep, depth + 1)?;
        }
        let children = self.ix.children.get(&pd).cloned().unwrap_or_default();
        for c in children {
            self.product(c, depth + 1)?;
        }
        self.path.pop();
        Ok(())
    }

    /// A representation: its items in order, then the representations related to it without
    /// a transformation (not those already on the path: the relation is symmetric).
    fn representation(&mut self, rep: u64, depth: usize) -> Result<(), String> {
        if !self.enter(rep, depth)? {
            return Err(format!(
                "#{rep}: the representation contains itself (reference cycle)"
            ));
        }
        let inst = self.g.get(rep, "a shape definition")?;
        let rec = inst
            .parts
            .iter()
            .find(|p| p.name.ends_with("REPRESENTATION"))
            .ok_or_else(|| format!("{} is not a representation", inst.what()))?;
        let attrs = super::graph::Attrs { inst, part: rec };
        let items = attrs.refs(1, "items")?;
        let context = attrs.reference(2, "context_of_items").ok();
        for it in items {
            self.item(it, context, depth + 1)?;
        }
        let related = self.ix.related.get(&rep).cloned().unwrap_or_default();
        for r in related {
            if !self.path.contains(&r) {
                self.representation(r, depth + 1)?;
            }
        }
        self.path.pop();
        Ok(())
    }

    /// A representation item: solids, surface models, shells, faces, mapped items.
    fn item(&mut self, label: u64, context: Option<u64>, depth: usize) -> Result<(), String> {
        let inst = self.g.get(label, "a representation")?;
        let what = inst.what();
        let name = inst
            .parts
            .first()
            .map(|p| p.name.as_str())
            .unwrap_or_default();
        if inst.is("ADVANCED_FACE") || inst.is("FACE_SURFACE") {
            if self.out.len() >= MAX_FACE_USES {
                return Err(format!("more than {MAX_FACE_USES} face uses"));
            }
            self.out.push(FaceUse {
                face: label,
                context,
            });
            return Ok(());
        }
        let follow: Vec<u64> = match (inst.is_complex(), name) {
            (false, "MANIFOLD_SOLID_BREP" | "FACETED_BREP") => {
                vec![inst.simple()?.reference(1, "outer")?]
            }
            (false, "BREP_WITH_VOIDS") => {
                let a = inst.simple()?;
                let mut v = vec![a.reference(1, "outer")?];
                v.extend(a.refs(2, "voids")?);
                v
            }
            (false, "SHELL_BASED_SURFACE_MODEL") => inst.simple()?.refs(1, "sbsm_boundary")?,
            (false, "CLOSED_SHELL" | "OPEN_SHELL") => inst.simple()?.refs(1, "cfs_faces")?,
            (false, "ORIENTED_CLOSED_SHELL" | "ORIENTED_OPEN_SHELL") => {
                vec![inst.simple()?.reference(2, "element")?]
            }
            (false, "ORIENTED_FACE") => vec![inst.simple()?.reference(2, "face_element")?],
            (false, "MAPPED_ITEM") => {
                let map = self
                    .g
                    .get(inst.simple()?.reference(1, "mapping_source")?, &what)?;
                let rep = map
                    .record("REPRESENTATION_MAP")?
                    .reference(1, "mapped_representation")?;
                return self.representation(rep, depth + 1);
            }
            _ => return Ok(()),
        };
        if !self.enter(label, depth)? {
            return Err(format!("{what}: reference cycle"));
        }
        for f in follow {
            self.item(f, context, depth + 1)?;
        }
        self.path.pop();
        Ok(())
    }
}
