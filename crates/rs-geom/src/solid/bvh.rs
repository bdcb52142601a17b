//! A bounding-volume hierarchy of patch boxes: which patches a ray may cross, which boxes
//! hold a point.

use rs_spline::Point3;

/// Boxes per leaf node.
const LEAF: usize = 4;

/// A node: its box and either two children or a run of items.
#[derive(Clone, Copy, Debug)]
struct Node {
    lo: Point3,
    hi: Point3,
    /// Leaf: `first .. first + count` of the item order; inner: `first` is the right child
    /// (the left one follows the node).
    first: u32,
    count: u32,
}

/// A hierarchy over boxes `(lo, hi)` given by index.
#[derive(Clone, Debug, Default)]
pub(super) struct Bvh {
    nodes: Vec<Node>,
    order: Vec<u32>,
    /// The items' boxes, in leaf order (`boxes[j]` is item `order[j]`'s).
    boxes: Vec<(Point3, Point3)>,
}

impl Bvh {
    /// The hierarchy of `boxes`: halved at the median of the boxes' centres along the widest
    /// side of their centres' box.
    pub(super) fn new(boxes: &[(Point3, Point3)]) -> Bvh {
        let mut bvh = Bvh {
            nodes: Vec::with_capacity(2 * boxes.len() / LEAF + 1),
            order: (0..boxes.len() as u32).collect(),
            boxes: Vec::new(),
        };
        if !boxes.is_empty() {
            let mut order = std::mem::take(&mut bvh.order);
            bvh.build(boxes, &mut order, 0);
            bvh.order = order;
        }
        bvh.boxes = bvh.order.iter().map(|&i| boxes[i as usize]).collect();
        bvh
    }

    fn build(&mut self, boxes: &[(Point3, Point3)], items: &mut [u32], first: usize) -> usize {
        let (lo, hi) = Point3::bounds(items.iter().flat_map(|&i| {
            let (a, b) = boxes[i as usize];
            [a, b]
        }))
        .unwrap_or_default();
        let me = self.nodes.len();
        self.nodes.push(Node {
            lo,
            hi,
            first: first as u32,
            count: items.len() as u32,
        });
        if items.len() <= LEAF {
            return me;
        }
        let centre = |i: u32| {
            let (a, b) = boxes[i as usize];
            (a + b) * 0.5
        };
        let (clo, chi) = Point3::bounds(items.iter().map(|&i| centre(i))).unwrap_or_default();
        let span = chi - clo;
        let axis = if span.x >= span.y && span.x >= span.z {
            0
        } else if span.y >= span.z {
            1
        } else {
            2
        };
        let mid = items.len() / 2;
        items.select_nth_unstable_by(mid, |&a, &b| centre(a)[axis].total_cmp(&centre(b)[axis]));
        let (left, right) = items.split_at_mut(mid);
        self.build(boxes, left, first);
        let r = self.build(boxes, right, first + mid);
        self.nodes[me].first = r as u32;
        self.nodes[me].count = 0;
        me
    }

    /// Calls `f(item)` for every box the ray `o + t d`, `t0 <= t <= t1`, meets (`inv` is
    /// `1 / d` componentwise).
    pub(super) fn along_ray(
        &self,
        o: Point3,
        inv: Point3,
        t0: f64,
        t1: f64,
        mut f: impl FnMut(u32),
    ) {
        self.visit(|lo, hi| ray_meets_box(o, inv, t0, t1, lo, hi), &mut f);
    }

    /// Calls `f(item)` for every box holding `p` (ends included).
    pub(super) fn holding(&self, p: Point3, mut f: impl FnMut(u32)) {
        self.visit(
            |lo, hi| (0..3).all(|k| p[k] >= lo[k] && p[k] <= hi[k]),
            &mut f,
        );
    }

    fn visit(&self, meets: impl Fn(Point3, Point3) -> bool, f: &mut impl FnMut(u32)) {
        if self.nodes.is_empty() {
            return;
        }
        // The tree is balanced (median splits): its depth is about log2(n / LEAF), far below
        // the stack's 64 slots for any number of boxes a u32 can count.
        let mut stack = [0u32; 64];
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let k = stack[top] as usize;
            let n = &self.nodes[k];
            if !meets(n.lo, n.hi) {
                continue;
            }
            if n.count > 0 {
                let s = n.first as usize;
                let e = s + n.count as usize;
                for (&i, &(lo, hi)) in self.order[s..e].iter().zip(&self.boxes[s..e]) {
                    if meets(lo, hi) {
                        f(i);
                    }
                }
            } else {
                stack[top] = n.first;
                stack[top + 1] = k as u32 + 1;
                top += 2;
            }
        }
    }
}

/// Whether the ray `o + t d` (`inv = 1 / d`), `t0 <= t <= t1`, meets the box `[lo, hi]` (the
/// slab test; a box the ray only touches counts).
pub(super) fn ray_meets_box(
    o: Point3,
    inv: Point3,
    t0: f64,
    t1: f64,
    lo: Point3,
    hi: Point3,
) -> bool {
    let slab = |o: f64, inv: f64, lo: f64, hi: f64| {
        let a = (lo - o) * inv;
        let b = (hi - o) * inv;
        if a <= b { (a, b) } else { (b, a) }
    };
    let (ax, bx) = slab(o.x, inv.x, lo.x, hi.x);
    let (ay, by) = slab(o.y, inv.y, lo.y, hi.y);
    let (az, bz) = slab(o.z, inv.z, lo.z, hi.z);
    let near = t0.max(ax).max(ay).max(az);
    let far = t1.min(bx).min(by).min(bz);
    near <= far
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every box a ray meets (by the slab test on each box alone) and every box holding a
    /// point is visited, and no other.
    #[test]
    fn the_hierarchy_visits_exactly_the_boxes_met() {
        let mut seed = 7u64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let boxes: Vec<(Point3, Point3)> = (0..500)
            .map(|_| {
                let c = Point3::new(next(), next(), next()) * 10.0;
                let h = Point3::new(next(), next(), next()) * 0.5;
                (c - h, c + h)
            })
            .collect();
        let bvh = Bvh::new(&boxes);
        for _ in 0..200 {
            let o = Point3::new(next(), next(), next()) * 10.0;
            let d = Point3::new(next() - 0.5, next() - 0.5, next() - 0.5);
            let inv = Point3::new(1.0 / d.x, 1.0 / d.y, 1.0 / d.z);
            let mut got = Vec::new();
            bvh.along_ray(o, inv, 0.0, f64::INFINITY, |i| got.push(i));
            got.sort_unstable();
            let want: Vec<u32> = (0..boxes.len() as u32)
                .filter(|&i| {
                    let (lo, hi) = boxes[i as usize];
                    ray_meets_box(o, inv, 0.0, f64::INFINITY, lo, hi)
                })
                .collect();
            assert_eq!(got, want);
            let mut got = Vec::new();
            bvh.holding(o, |i| got.push(i));
            got.sort_unstable();
            let want: Vec<u32> = (0..boxes.len() as u32)
                .filter(|&i| {
                    let (lo, hi) = boxes[i as usize];
                    (0..3).all(|k| o[k] >= lo[k] && o[k] <= hi[k])
                })
                .collect();
            assert_eq!(got, want);
        }
    }
}
