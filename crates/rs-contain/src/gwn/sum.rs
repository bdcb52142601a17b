//! Adding up the angles that chords subtend at a query point, without one `atan2` per chord.
//!
//! With `theta(p)` the polar angle of `p - q` in `(-pi, pi]` (the cut along the ray from `q`
//! towards `-x`), the signed angle a chord `a -> b` subtends at `q` is
//! `theta(b) - theta(a) + 2 pi k`, where `k` is `+1` if the chord crosses the cut downwards,
//! `-1` upwards, `0` otherwise. Over a chain of chords the `theta` terms telescope, so the
//! winding number of a chain from `s` to `e` is the signed crossing count `sum k` (exact
//! integers) plus `(theta(e) - theta(s)) / 2 pi`, which vanishes for a closed chain. Deciding
//! `k` takes two comparisons for most chords and one cross product for the rest.
//!
//! A chord through `q` (the query on the curve) has no defined angle; the paper's convention
//! gives it its own value (0 on an open chord, the tangent formula at an end point). Such a
//! *special* chord contributes its value and takes back its `theta` terms, so the telescoping
//! still holds.

use std::f64::consts::TAU;

use rs_spline::Point;

/// Where the adaptive algorithm sends the chords it replaces a curve by.
pub(crate) trait ChordSink {
    /// A chord `a -> b` whose angle at the query is the curve's (the query is not on it, or
    /// is and then the chord's angle convention applies).
    fn chord(&mut self, a: Point, b: Point);
    /// A piece `a -> b` through the query whose contribution is `value` (turns), by a
    /// coincidence convention.
    fn special(&mut self, value: f64, a: Point, b: Point);
    /// Whether the sink records that the query may be near the curve
    /// ([`ChordSink::mark_near`]); the tests for it are compiled out of sinks that do not.
    const TRACKS_NEAR: bool = false;
    /// How far from every settled sub-curve's control polygon (or box) the query must be for
    /// it not to be near the curve.
    fn reach(&self) -> f64 {
        0.0
    }
    /// The query may be within [`ChordSink::reach`] of the curve.
    fn mark_near(&mut self) {}
    /// Whether the sink takes a sub-curve's signed crossings of the cut whole
    /// ([`ChordSink::crossings`]): then the walks settle a polynomial sub-curve monotone in
    /// `y` from the root of `y(t) = q.y` instead of halving it (see
    /// [`super::monotone::monotone_crossing`]).
    const COUNTS_CROSSINGS: bool = false;
    /// Adds `k`, a sub-curve's signed crossings of the cut (what its chords would add).
    fn crossings(&mut self, _k: i64) {}
}

/// Below this, `u . v` and `u x v` of a chain's ends may have lost digits to underflow.
const TINY_PRODUCT: f64 = 1e-280;

/// [`ChainEnds::add_to`] takes queries at a distance in `[MIN_REACH, MAX_REACH]` from
/// the ends' box (the products `u . v`, `u x v` then neither overflow nor lose digits).
const MIN_REACH: f64 = 1e-120;
/// See [`MIN_REACH`].
const MAX_REACH: f64 = 1e120;
/// A scaled factor below this (an end within about `1e-15` of the reach from the query) takes
/// its own `atan2`s; [`RENORMALISE`] factors above it keep the product a normal number.
const MIN_FACTOR: f64 = 1e-30;
/// Factors between renormalisations of the running product.
const RENORMALISE: usize = 8;
/// Queries whose chain ends [`ChainEnds::add_to`] adds side by side.
pub(crate) const BATCH: usize = 8;

/// The two ends of every open chain of a curve collection, with the box of all of them.
#[derive(Clone, Debug, Default)]
pub(crate) struct ChainEnds {
    ends: Vec<(Point, Point)>,
    lo: Point,
    hi: Point,
}

impl ChainEnds {
    /// The chains from `s` to `e` of `ends`.
    pub(crate) fn new(ends: Vec<(Point, Point)>) -> Self {
        let mut all = ends.iter().flat_map(|&(s, e)| [s, e]);
        let first = all.next().unwrap_or_default();
        let (lo, hi) = all.fold((first, first), |(lo, hi), p| {
            (
                Point::new(lo.x.min(p.x), lo.y.min(p.y)),
                Point::new(hi.x.max(p.x), hi.y.max(p.y)),
            )
        });
        Self { ends, lo, hi }
    }

    /// No open chain.
    pub(crate) fn is_empty(&self) -> bool {
        self.ends.is_empty()
    }

    /// Each open chain's start and end.
    pub(crate) fn ends(&self) -> &[(Point, Point)] {
        &self.ends
    }

    /// Adds to each of `sums` the turns of every chain: `(theta(e) - theta(s)) / 2 pi` for each
    /// chain from `s` to `e`, with one `atan2` for all of them. Each term is
    /// `angle(s -> e) - 2 pi k(s -> e)`; the angles are added as the argument of the product of
    /// the complex numbers `(u . v, u x v)` (`u = s - q`, `v = e - q`), counting the turns the
    /// product's argument wraps past `pi`, so no angle is lost to the branch cut.
    ///
    /// The factors are scaled by one power of two per query (from the distance between `q` and
    /// the ends' box) so that each is smaller than 1, and the product is renormalised every
    /// [`RENORMALISE`] factors; the loop holds no call and no data-dependent branch. A query
    /// with a chain it cannot multiply in (`q` on the segment `s e`, or an end so close to `q`
    /// that the factor is below [`MIN_FACTOR`]: that factor turns the product into NaN), and a
    /// query whose distance to the ends' box is outside `[MIN_REACH, MAX_REACH]` (or not a
    /// number), take [`WindingSum::add_chain_ends_one_by_one`] instead.
    ///
    /// Full groups of [`BATCH`] sums run side by side: one pass over the chains, each step done
    /// for all of them at once (which the compiler turns into vector instructions). Each sum
    /// gets exactly what it would get on its own.
    pub(crate) fn add_to(&self, sums: &mut [WindingSum]) {
        // Compiled a second time for AVX2 (and FMA, which the compiler does not fuse into
        // plain Rust multiplications and additions: the same values), chosen at run time.
        pulp::Arch::new().dispatch(AddTo { ends: self, sums });
    }

    /// [`ChainEnds::add_to`], inlined into each instruction set's copy.
    #[inline(always)]
    fn add_to_all(&self, sums: &mut [WindingSum]) {
        let mut groups = sums.chunks_exact_mut(BATCH);
        for group in groups.by_ref() {
            self.add_to_group::<BATCH>(group);
        }
        for sum in groups.into_remainder() {
            self.add_to_group::<1>(std::slice::from_mut(sum));
        }
    }

    /// [`ChainEnds::add_to`] for at most `L` sums, in `L` lanes.
    #[inline(always)]
    fn add_to_group<const L: usize>(&self, sums: &mut [WindingSum]) {
        let n = sums.len().min(L);
        // A lane out of reach keeps scale 0: its factors are 0 or NaN, unusable, and it takes
        // the one-by-one sum below.
        let (mut qx, mut qy, mut scale, mut in_reach) =
            ([0.0f64; L], [0.0f64; L], [0.0f64; L], [false; L]);
        for (k, sum) in sums.iter().take(n).enumerate() {
            let reach = self.reach(sum.q);
            (qx[k], qy[k]) = (sum.q.x, sum.q.y);
            in_reach[k] = reach > MIN_REACH && reach < MAX_REACH;
            if in_reach[k] {
                // With 2^e <= reach < 2^(e+1): |u|, |v| <= sqrt(2) reach, so every factor's
                // size |u| |v| < 8 4^e is below 1 once scaled by 4^-e / 8.
                let s = inverse_power_of_two(reach);
                scale[k] = 0.125 * s * s;
            }
        }
        // Lanes past `n` and queries out of reach run along harmlessly and are dropped.
        let (mut re, mut im) = ([1.0f64; L], [0.0f64; L]);
        let mut wraps = [0.0f64; L];
        for (i, &(a, b)) in self.ends.iter().enumerate() {
            for k in 0..L {
                let q = Point::new(qx[k], qy[k]);
                let (u, v) = (a - q, b - q);
                let (d, c, usable) = scaled_factor(u, v, scale[k]);
                // An unusable factor makes the lane's product NaN (which marks the lane for
                // the one-by-one sum below); its flags are then all false.
                let (d, c) = if usable { (d, c) } else { (f64::NAN, f64::NAN) };
                wraps[k] += multiply_chain(&mut re[k], &mut im[k], u, v, d, c);
            }
            if i % RENORMALISE == RENORMALISE - 1 {
                for k in 0..L {
                    (re[k], im[k]) = renormalised(re[k], im[k]);
                }
            }
        }
        // The lanes' arguments side by side (vectorised like the loop above).
        let mut args = [0.0f64; L];
        for k in 0..L {
            args[k] = argument(re[k], im[k]);
        }
        for (k, sum) in sums.iter_mut().take(n).enumerate() {
            // A usable factor keeps the product a finite number (the scale and the
            // renormalisation see to it), so a NaN argument means an unusable one.
            if !in_reach[k] || args[k].is_nan() {
                sum.add_chain_ends_one_by_one(&self.ends);
                continue;
            }
            // Counts of at most one per chain: exact in f64.
            sum.add_turns(args[k], wraps[k] as i64);
        }
    }

    /// The largest coordinate difference between `q` and a point of the ends' box: at least
    /// every `|u.x|`, `|u.y|` of an end `u` relative to `q`.
    ///
    /// `max(|q.x - lo.x|, |q.x - hi.x|)` is `max(q.x - lo.x, hi.x - q.x)` (the two add up to
    /// `hi.x - lo.x >= 0`), so no absolute value is taken.
    #[inline(always)]
    fn reach(&self, q: Point) -> f64 {
        (q.x - self.lo.x)
            .max(self.hi.x - q.x)
            .max(q.y - self.lo.y)
            .max(self.hi.y - q.y)
    }
}

/// [`ChainEnds::add_to`] as an operation `pulp` runs with the best instruction set at hand.
struct AddTo<'a> {
    ends: &'a ChainEnds,
    sums: &'a mut [WindingSum],
}

impl pulp::WithSimd for AddTo<'_> {
    type Output = ();
    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) {
        self.ends.add_to_all(self.sums);
    }
}

/// The factor `(u . v, u x v) * scale` of a chain whose ends are `u`, `v` relative to the
/// query, and whether the product may take it: not on the negative real axis (the query on
/// the segment between the ends) and not below [`MIN_FACTOR`] (nor NaN).
#[inline(always)]
fn scaled_factor(u: Point, v: Point, scale: f64) -> (f64, f64, bool) {
    let (d, c) = (u.dot(v) * scale, u.cross(v) * scale);
    // `|d| > m or |c| > m` is `max(|d|, |c|) > m` (also when one is NaN), without the max.
    let usable = !((c == 0.0) & (d <= 0.0)) & ((d.abs() > MIN_FACTOR) | (c.abs() > MIN_FACTOR));
    (d, c, usable)
}

/// One chain's step of the product of [`ChainEnds::add_to`]: multiplies `re + i im` by the
/// chain's factor `d + i c` (a positive multiple of `(u . v, u x v)`, not on the negative real
/// axis; `(1, 0)` for none) and returns the whole turns this adds: the wrap of the product's
/// argument past `pi` (`+1` when two arguments in `[0, pi]` and `(0, pi)` land below the real
/// axis, `-1` the other way), less the chord's crossing `k(s -> e)` of the cut. Branch-free:
/// the signs are as good as random.
///
/// Both counts have one form: a step `t` in `{-1, 0, 1}` between two "upper half" flags (the
/// chord's ends for `k`, the product before and after for the wrap) that counts only when it
/// turns the way `c` does (`t c > 0`): `+1` needs `c > 0`, `-1` needs `c < 0`.
#[inline(always)]
fn multiply_chain(re: &mut f64, im: &mut f64, u: Point, v: Point, d: f64, c: f64) -> f64 {
    let one = |b: bool| if b { 1.0 } else { 0.0 };
    let turning = |t: f64| if t * c > 0.0 { t } else { 0.0 };
    let chord = turning(one(u.y >= 0.0) - one(v.y >= 0.0));
    let (nre, nim) = (*re * d - *im * c, *re * c + *im * d);
    let wrap = turning(one(*im >= 0.0) - one(nim >= 0.0));
    (*re, *im) = (nre, nim);
    wrap - chord
}

/// `re + i im` scaled by a power of two (exact) so that its larger part lies in `[1, 2)`.
#[inline(always)]
fn renormalised(re: f64, im: f64) -> (f64, f64) {
    let s = inverse_power_of_two(re.abs().max(im.abs()));
    (re * s, im * s)
}

/// `atan(j / 16)` for `j = 0, ..., 16`, correctly rounded (checked against `f64::atan` in the
/// tests).
const ATAN_SIXTEENTHS: [f64; 17] = [
    0.0,
    0.06241880999595735,
    0.12435499454676144,
    0.18534794999569476,
    0.24497866312686414,
    0.3028848683749714,
    0.35877067027057225,
    0.4124104415973873,
    0.4636476090008061,
    0.5123894603107377,
    0.5585993153435624,
    0.6022873461349642,
    0.6435011087932844,
    0.6823165548747481,
    0.7188299996216245,
    0.7531512809621944,
    std::f64::consts::FRAC_PI_4,
];

/// The argument of `re + i im` in `(-pi, pi]` (`pi` on the negative real axis whatever the
/// zero's sign, 0 at 0), within a few units in the last place of `pi`, in straight-line code the
/// compiler can vectorise over lanes (`f64::atan2` is a call per lane).
///
/// With `t = min(|re|, |im|) / max(|re|, |im|)` in `[0, 1]` and `c = j / 16` the nearest
/// sixteenth, `atan t = atan c + atan r` with `r = (t - c) / (1 + t c)`, `|r| <= 1/32`, where five
/// terms of `r - r^3/3 + r^5/5 - ...` leave an error below `1e-18`; then the octant and quadrant
/// are undone.
#[inline(always)]
fn argument(re: f64, im: f64) -> f64 {
    use std::f64::consts::{FRAC_PI_2, PI};
    let (ax, ay) = (re.abs(), im.abs());
    let steep = ay > ax;
    let (num, den) = if steep { (ax, ay) } else { (ay, ax) };
    let t = if den == 0.0 { 0.0 } else { num / den };
    // t in [0, 1]: adding 1.5 * 2^52 rounds 16 t to the nearest integer, which the low bits
    // then hold (no float-to-integer conversion: about 18 instructions per lane in the
    // baseline build, callgrind); NaN gives some j <= 16 and a NaN result.
    const ROUND: f64 = 6_755_399_441_055_744.0;
    let m = t * 16.0 + ROUND;
    let j = ((m.to_bits() & 0x1f) as usize).min(16);
    let c = (m - ROUND) * 0.0625;
    let r = (t - c) / (1.0 + t * c);
    let r2 = r * r;
    let series =
        r * (1.0 - r2 * (1.0 / 3.0 - r2 * (1.0 / 5.0 - r2 * (1.0 / 7.0 - r2 * (1.0 / 9.0)))));
    let a = ATAN_SIXTEENTHS[j] + series;
    let a = if steep { FRAC_PI_2 - a } else { a };
    let a = if re < 0.0 { PI - a } else { a };
    if im < 0.0 { -a } else { a }
}

/// `2^-k` for the `k` with `2^k <= x < 2^(k+1)`, for a normal `x < 2^1023` (the callers' are
/// below `1e301`): multiplying by it is exact. (0 for an infinite or NaN `x`.)
#[inline(always)]
fn inverse_power_of_two(x: f64) -> f64 {
    let exponent = (x.to_bits() >> 52) & 0x7ff;
    f64::from_bits(2046u64.saturating_sub(exponent) << 52)
}

/// `theta(p - q)`, with `theta(0) = 0`.
fn theta(q: Point, p: Point) -> f64 {
    (p.y - q.y).atan2(p.x - q.x)
}

/// Signed angle from `a` to `b` in `(-pi, pi]`.
pub(crate) fn signed_angle(a: Point, b: Point) -> f64 {
    a.cross(b).atan2(a.dot(b))
}

/// Angle subtended at `q` by the chord from `a` to `b`, with the coincidence convention: a
/// query on the closed chord (angle +-pi, the average of the two sides being 0) contributes 0.
pub(crate) fn chord_angle(q: Point, a: Point, b: Point) -> f64 {
    let (u, v) = (a - q, b - q);
    if u.cross(v) == 0.0 && u.dot(v) <= 0.0 {
        return 0.0;
    }
    signed_angle(u, v)
}

/// The winding number at one query point as signed crossings of the cut plus a fractional
/// part (see the module documentation).
#[derive(Clone, Copy, Debug)]
pub(crate) struct WindingSum {
    q: Point,
    crossings: i64,
    turns: f64,
    /// See [`ChordSink::reach`].
    reach: f64,
    /// Some settled sub-curve may lie within `reach` of `q`.
    near: bool,
}

impl WindingSum {
    /// Nothing added yet.
    pub(crate) fn new(q: Point) -> Self {
        Self::tracking(q, 0.0)
    }

    /// Nothing added yet; records whether a settled sub-curve may lie within `reach` of `q`.
    pub(crate) fn tracking(q: Point, reach: f64) -> Self {
        Self {
            q,
            crossings: 0,
            turns: 0.0,
            reach,
            near: false,
        }
    }

    /// `crossings` added already, as the walk counts them at a query in a far cell (see
    /// `far_cells`): nothing else, and no curve within reach.
    pub(crate) fn with_crossings(q: Point, reach: f64, crossings: i64) -> Self {
        Self {
            crossings,
            ..Self::tracking(q, reach)
        }
    }

    /// The crossings counted, if nothing else was added (no curve through or at the query).
    pub(crate) fn crossings_alone(&self) -> Option<i64> {
        (self.turns == 0.0).then_some(self.crossings)
    }

    /// May some curve added lie within the reach of the query (see
    /// [`WindingSum::tracking`])? False means every one is farther.
    pub(crate) fn near(&self) -> bool {
        self.near
    }

    /// `+1` or `-1` for a chord lying wholly left of the query (`max(a.x, b.x) < q.x`) that
    /// crosses the query's height downwards or upwards, else `0`: a comparison per end.
    #[inline]
    pub(crate) fn left_crossing(&mut self, a: Point, b: Point) {
        self.crossings += chord_crossing(a.y, b.y, self.q.y);
    }

    /// Adds `n` signed crossings of chords lying wholly left of the query, counted before
    /// (the sum of their [`WindingSum::left_crossing`]s).
    #[inline]
    pub(crate) fn add_left_crossings(&mut self, n: i64) {
        self.crossings += n;
    }

    /// [`ChainEnds::add_to`] scaling each factor by its own power of two: any finite
    /// coordinates. A chain with `q` on the segment `s e` or an end within `1e-140` of `q`
    /// takes its two `atan2`s.
    pub(crate) fn add_chain_ends_one_by_one(&mut self, ends: &[(Point, Point)]) {
        let (mut re, mut im, mut wraps) = (1.0f64, 0.0f64, 0i64);
        for (i, &(s, e)) in ends.iter().enumerate() {
            let (u, v) = (s - self.q, e - self.q);
            let (d, c) = (u.dot(v), u.cross(v));
            let size = d.abs().max(c.abs());
            if (c == 0.0 && d <= 0.0) || !(size > TINY_PRODUCT && size.is_finite()) {
                self.turns += (theta(self.q, e) - theta(self.q, s)) / TAU;
                continue;
            }
            // Scale by a power of two (exact) to keep the product in range.
            let scale = inverse_power_of_two(size);
            // At most two turns per chain: exact in f64.
            wraps += multiply_chain(&mut re, &mut im, u, v, d * scale, c * scale) as i64;
            if i % 64 == 63 {
                (re, im) = renormalised(re, im);
            }
        }
        self.add_product(re, im, wraps);
    }

    /// Adds a product's argument ([`argument`]) and the turns it wrapped.
    fn add_product(&mut self, re: f64, im: f64, wraps: i64) {
        self.add_turns(argument(re, im), wraps);
    }

    /// Adds an argument `arg` (radians) and `wraps` whole turns.
    fn add_turns(&mut self, arg: f64, wraps: i64) {
        self.crossings += wraps;
        self.turns += arg / TAU;
    }

    /// The query point.
    pub(crate) fn q(&self) -> Point {
        self.q
    }

    /// The winding number.
    pub(crate) fn value(&self) -> f64 {
        self.crossings as f64 + self.turns
    }
}

/// `k` of a chord whose ends are `u`, `v` relative to the query, with `c = u x v` (the chord
/// must not pass through the query): `+1` across the cut downwards, `-1` upwards.
#[inline]
pub(crate) fn cut_crossing(u: Point, v: Point, c: f64) -> i32 {
    let (up_u, up_v) = (u.y >= 0.0, v.y >= 0.0);
    if up_u && !up_v && c > 0.0 {
        1
    } else if !up_u && up_v && c < 0.0 {
        -1
    } else {
        0
    }
}

impl ChordSink for WindingSum {
    #[inline]
    fn chord(&mut self, a: Point, b: Point) {
        let (u, v) = (a - self.q, b - self.q);
        let (up_u, up_v) = (u.y >= 0.0, v.y >= 0.0);
        if up_u == up_v && u.y != 0.0 && v.y != 0.0 {
            return; // both strictly on one side: no crossing, q not on the chord
        }
        let c = u.cross(v);
        if c == 0.0 && u.dot(v) <= 0.0 {
            // q on the closed chord: the convention gives 0.
            self.special(0.0, a, b);
            return;
        }
        self.crossings += i64::from(cut_crossing(u, v, c));
    }

    fn special(&mut self, value: f64, a: Point, b: Point) {
        self.turns += value - (theta(self.q, b) - theta(self.q, a)) / TAU;
    }

    const TRACKS_NEAR: bool = true;

    #[inline]
    fn reach(&self) -> f64 {
        self.reach
    }

    #[inline]
    fn mark_near(&mut self) {
        self.near = true;
    }
}

/// A [`WindingSum`] that takes a sub-curve's crossings whole ([`ChordSink::COUNTS_CROSSINGS`]):
/// the fast field's walks. The crossings are the chords' (the same whole number; a sub-curve
/// settled by its root adds no coincidence term, `q` being certainly off it), and so is the
/// value; the reference field ([`super::WindingField`]) keeps the paper's walk, halving every
/// sub-curve. The near mark may stay unset where the walk below a sub-curve settled by its
/// root would have set it (a box or control polygon within reach of `q`, the curve itself
/// farther): that changes no value, as a query in the band is within the band's tolerance and
/// gaps of a curve, less than twice the reach from every sub-curve holding its nearest point,
/// which the root then never settles, so the walk through them still sets the mark.
pub(crate) struct CrossingSum<'a>(pub(crate) &'a mut WindingSum);

impl ChordSink for CrossingSum<'_> {
    #[inline(always)]
    fn chord(&mut self, a: Point, b: Point) {
        self.0.chord(a, b);
    }

    #[inline(always)]
    fn special(&mut self, value: f64, a: Point, b: Point) {
        self.0.special(value, a, b);
    }

    const TRACKS_NEAR: bool = true;

    #[inline(always)]
    fn reach(&self) -> f64 {
        self.0.reach
    }

    #[inline(always)]
    fn mark_near(&mut self) {
        self.0.near = true;
    }

    const COUNTS_CROSSINGS: bool = true;

    #[inline(always)]
    fn crossings(&mut self, k: i64) {
        self.0.crossings += k;
    }
}

/// The angles themselves, one `atan2` per chord: the paper's direct sum, for one curve on its
/// own (no chain to telescope over).
#[derive(Clone, Copy, Debug)]
pub(crate) struct AngleSum {
    q: Point,
    /// The sum, in turns.
    pub(crate) turns: f64,
}

impl AngleSum {
    /// Nothing added yet.
    pub(crate) fn new(q: Point) -> Self {
        Self { q, turns: 0.0 }
    }
}

impl ChordSink for AngleSum {
    fn chord(&mut self, a: Point, b: Point) {
        self.turns += chord_angle(self.q, a, b) / TAU;
    }

    fn special(&mut self, value: f64, _a: Point, _b: Point) {
        self.turns += value;
    }
}

/// The signed crossing of the height `q_y` by a chord from height `a_y` to `b_y` lying wholly
/// left of the query: `+1` downwards, `-1` upwards, `0` if it does not cross (an end with
/// `y >= q_y` counts as above: the one rule every sum of chords' crossings keeps).
#[inline(always)]
pub(crate) fn chord_crossing(a_y: f64, b_y: f64, q_y: f64) -> i64 {
    i64::from(a_y >= q_y) - i64::from(b_y >= q_y)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The crossing sum of a chain equals the sum of its chords' angles.
    #[test]
    fn crossings_and_ends_equal_the_angle_sum() {
        let chain = [
            Point::new(2.0, -1.0),
            Point::new(-1.0, 3.0),
            Point::new(-2.0, -2.0),
            Point::new(1.0, -3.0),
            Point::new(3.0, 2.0),
            Point::new(0.5, 0.0),
            Point::new(-4.0, 0.0),
        ];
        let queries = [
            Point::new(0.0, 0.0),
            Point::new(0.1, -0.3),
            Point::new(-1.5, 0.0),
            Point::new(5.0, 0.0),
            Point::new(0.0, 3.0),
            Point::new(-1.0, 3.0), // a vertex
            Point::new(-2.5, 0.0), // on the last chord
        ];
        for q in queries {
            let (mut w, mut a) = (WindingSum::new(q), AngleSum::new(q));
            for c in chain.windows(2) {
                w.chord(c[0], c[1]);
                a.chord(c[0], c[1]);
            }
            ChainEnds::new(vec![(chain[0], chain[chain.len() - 1])])
                .add_to(std::slice::from_mut(&mut w));
            assert!(
                (w.value() - a.turns).abs() < 1e-15,
                "{q:?}: {} vs {}",
                w.value(),
                a.turns
            );
        }
    }

    /// Many chains at once, against the sum of their ends' angles: the product's argument
    /// wraps many times.
    #[test]
    fn chain_ends_add_up_through_the_product() {
        let q = Point::new(0.3, -0.1);
        let mut ends = Vec::new();
        for i in 0..200 {
            let t = i as f64 * 0.37;
            let r = 1e-3 * (1.0 + i as f64);
            ends.push((
                Point::new(r * t.cos(), r * t.sin() + 1e-9 * i as f64) + q,
                Point::new(-r * (2.0 * t).sin(), 3e5 * r * t.cos()) + q,
            ));
        }
        ends.push((q + Point::new(1.0, 0.0), q + Point::new(-2.0, 0.0))); // q on the segment
        ends.push((q, q + Point::new(0.0, 1.0))); // an end at q
        let mut w = WindingSum::new(q);
        ChainEnds::new(ends.clone()).add_to(std::slice::from_mut(&mut w));
        let exact: f64 = ends
            .iter()
            .map(|&(s, e)| (theta(q, e) - theta(q, s)) / TAU)
            .sum();
        assert!(
            (w.value() - exact).abs() < 1e-12,
            "{} vs {exact}",
            w.value()
        );
    }

    /// Queries side by side (two full groups and a remainder, some out of reach, some at an
    /// end, on a segment or within 1e-20 of an end) get the sum of their ends' angles.
    #[test]
    fn batched_queries_add_their_own_turns() {
        let ends: Vec<(Point, Point)> = (0..13)
            .map(|i| {
                let t = i as f64 * 0.71;
                (
                    Point::new(t.cos(), 0.5 * t.sin()),
                    Point::new(2.0 * (1.3 * t).sin(), t.cos() - 0.2),
                )
            })
            .collect();
        let chains = ChainEnds::new(ends.clone());
        let (s0, e0) = ends[0];
        let mut queries: Vec<Point> = (0..19)
            .map(|i| Point::new(-3.0 + 0.31 * i as f64, 1.7 - 0.23 * i as f64))
            .collect();
        queries.extend([
            s0,                             // at an end
            (s0 + e0) * 0.5,                // on a chain's segment (up to rounding)
            e0 + Point::new(1e-20, -1e-20), // a factor below MIN_FACTOR
            Point::new(1e130, 0.2),         // out of reach
            Point::new(0.3, -2e-125),       // in reach
            Point::new(-5.0, e0.y),         // level with an end
        ]);
        let mut sums: Vec<WindingSum> = queries.iter().map(|&q| WindingSum::new(q)).collect();
        chains.add_to(&mut sums);
        for (q, sum) in queries.iter().zip(&sums) {
            let exact: f64 = ends
                .iter()
                .map(|&(s, e)| (theta(*q, e) - theta(*q, s)) / TAU)
                .sum();
            assert!(
                (sum.value() - exact).abs() < 1e-12,
                "{q:?}: {} vs {exact}",
                sum.value()
            );
            // One at a time gives the same bits.
            let mut one = WindingSum::new(*q);
            chains.add_to(std::slice::from_mut(&mut one));
            assert_eq!(one.value().to_bits(), sum.value().to_bits(), "{q:?}");
        }
    }

    /// The copy `add_to` runs (compiled for the widest instruction set the CPU has: AVX-512
    /// or AVX2 on most x86-64), and on x86-64 each of the AVX2 and AVX-512 copies the CPU can
    /// run, give the same bits as the copy built for the baseline target.
    #[test]
    fn the_dispatched_product_equals_the_baseline_one() {
        let ends: Vec<(Point, Point)> = (0..37)
            .map(|i| {
                let t = i as f64 * 0.61;
                (
                    Point::new(3.0 * t.cos(), 1.7 * (1.9 * t).sin()),
                    Point::new(2.2 * (0.7 * t).sin(), t.cos() - 0.4 * t),
                )
            })
            .collect();
        let chains = ChainEnds::new(ends);
        let queries: Vec<WindingSum> = (0..203)
            .map(|i| {
                let s = i as f64 * 0.173;
                WindingSum::new(Point::new(4.0 * s.sin(), 3.0 * (1.3 * s).cos() - 0.01 * s))
            })
            .collect();
        let mut baseline = queries.clone();
        chains.add_to_all(&mut baseline);
        let mut copies = vec![("dispatched", queries.clone())];
        chains.add_to(&mut copies[0].1);
        #[cfg(target_arch = "x86_64")]
        {
            // The copy compiled for `simd`'s instruction set, on the queries.
            fn with<S: pulp::Simd>(
                simd: S,
                chains: &ChainEnds,
                queries: &[WindingSum],
            ) -> Vec<WindingSum> {
                let mut sums = queries.to_vec();
                simd.vectorize(AddTo {
                    ends: chains,
                    sums: &mut sums,
                });
                sums
            }
            if let Some(simd) = pulp::x86::V3::try_new() {
                copies.push(("AVX2", with(simd, &chains, &queries)));
            }
            if let Some(simd) = pulp::x86::V4::try_new() {
                copies.push(("AVX-512", with(simd, &chains, &queries)));
            }
        }
        for (name, sums) in &copies {
            for (a, b) in sums.iter().zip(&baseline) {
                assert_eq!(a.value().to_bits(), b.value().to_bits(), "{name} {:?}", a.q);
            }
        }
        eprintln!(
            "compared with the baseline: {:?}",
            copies.iter().map(|c| c.0).collect::<Vec<_>>()
        );
    }

    /// The vectorisable argument against `f64::atan2` all round the circle, on the axes and at
    /// the octant boundaries, and its table against `f64::atan`.
    #[test]
    fn argument_matches_atan2() {
        for (j, &a) in ATAN_SIXTEENTHS.iter().enumerate() {
            assert_eq!(a, (j as f64 / 16.0).atan(), "{j}");
        }
        let mut worst = 0.0f64;
        for i in 0..20_000 {
            let phi =
                -std::f64::consts::PI + (i as f64 + 0.37) * (std::f64::consts::TAU / 20_000.0);
            for scale in [1e-200, 3e-5, 1.0, 7e150] {
                let (re, im) = (scale * phi.cos(), scale * phi.sin());
                worst = worst.max((argument(re, im) - im.atan2(re)).abs());
            }
        }
        assert!(worst < 4.0 * f64::EPSILON, "{worst:e}");
        let pi = std::f64::consts::PI;
        for (re, im, want) in [
            (1.0, 0.0, 0.0),
            (0.0, 1.0, pi / 2.0),
            (-1.0, 0.0, pi),
            (-1.0, -0.0, pi),
            (0.0, -1.0, -pi / 2.0),
            (1.0, 1.0, pi / 4.0),
            (-1.0, -1.0, -0.75 * pi),
            (0.0, 0.0, 0.0),
        ] {
            assert!(
                (argument(re, im) - want).abs() <= 2.0 * f64::EPSILON,
                "{re} {im}"
            );
        }
        assert!(argument(f64::NAN, 1.0).is_nan());
    }

    #[test]
    fn powers_of_two_scale_exactly() {
        for x in [1.0, 3.0, 0.7, 1e-300, 2.5e300, f64::MIN_POSITIVE] {
            let s = inverse_power_of_two(x);
            assert!((1.0..2.0).contains(&(x * s)), "{x}: {}", x * s);
        }
    }

    #[test]
    fn a_closed_chain_needs_no_angle() {
        let square = [
            Point::new(0.0, 0.0),
            Point::new(1.0, 0.0),
            Point::new(1.0, 1.0),
            Point::new(0.0, 1.0),
            Point::new(0.0, 0.0),
        ];
        let mut w = WindingSum::new(Point::new(0.5, 0.5));
        for c in square.windows(2) {
            w.chord(c[0], c[1]);
        }
        assert_eq!(w.value(), 1.0);
        let mut w = WindingSum::new(Point::new(1.5, 0.0));
        for c in square.windows(2) {
            w.chord(c[0], c[1]);
        }
        assert_eq!(w.value(), 0.0);
    }
}
