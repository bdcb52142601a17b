//! The IGES reader's errors. Each is one line naming where the problem is: the line of the
//! file for the file's structure, the directory entry (`DE 57 (126 rational B-spline curve)`)
//! and its parameter for an entity. Problems of the file's structure are file-level
//! ([`crate::IoError::Cad`] with this message); problems of an entity refuse the faces that use
//! it (`FaceError::Read`, whose [`rs_geom::brep::ReadError`] holds this error).

use rs_geom::GeomError;
use rs_spline::SplineError;
use thiserror::Error;

/// What is wrong with one field of a parameter record or of the global section.
#[derive(Clone, Debug, Error, PartialEq)]
#[non_exhaustive]
pub enum FieldProblem {
    /// The record ends before the field.
    #[error("the record ends before it")]
    Missing,
    /// Text that is not a number.
    #[error("{0:?} is not a number")]
    NotANumber(String),
    /// A number beyond the range of `f64` (or `NaN`, `inf`).
    #[error("{0:?} is not a finite number")]
    NotFinite(String),
    /// Text that is not an integer.
    #[error("{0:?} is not an integer")]
    NotAnInteger(String),
    /// An integer beyond the range of `i64`.
    #[error("{0:?} is out of range")]
    IntegerOutOfRange(String),
    /// A Hollerith string where a number is expected.
    #[error("a string where a number is expected")]
    StringForNumber,
    /// A Hollerith string where an integer is expected.
    #[error("a string where an integer is expected")]
    StringForInteger,
    /// A count below zero.
    #[error("negative count {0}")]
    NegativeCount(i64),
    /// A pointer beyond the addressable range.
    #[error("pointer out of range")]
    PointerOutOfRange,
    /// A count of items that the rest of the record cannot hold.
    #[error("count {count} is more than the {left} fields left in the record")]
    CountTooLarge {
        /// The count read.
        count: usize,
        /// How many items of its size the rest of the record can hold at most.
        left: usize,
    },
    /// A Hollerith string longer than the rest of the record.
    #[error("Hollerith string of {0} characters runs past the end of the record")]
    HollerithPastEnd(usize),
    /// Something other than a delimiter after a Hollerith string.
    #[error("{0:?} after a Hollerith string (expected a delimiter)")]
    AfterHollerith(char),
    /// A B-spline degree outside the range accepted.
    #[error("degree {degree} (1 to {max} accepted)")]
    Degree {
        /// The degree read.
        degree: usize,
        /// The largest degree accepted.
        max: usize,
    },
    /// A 106's interpretation flag that is not 1, 2 or 3.
    #[error("interpretation flag {0} (expected 1, 2 or 3)")]
    InterpretationFlag(i64),
    /// A path of fewer than two points.
    #[error("{0} points (a path needs 2)")]
    TooFewPoints(usize),
}

/// Why an IGES file, or an entity in it, cannot be read.
#[derive(Clone, Debug, Error)]
#[non_exhaustive]
pub enum IgesError {
    // --- the file's structure (file-level errors) -------------------------------------------
    /// A file without records.
    #[error("empty file (no records)")]
    Empty,
    /// The compressed ASCII form.
    #[error(
        "the compressed ASCII form (flag section C) is not supported; write the fixed 80-column form"
    )]
    Compressed,
    /// The binary form.
    #[error("the binary form is not supported; write the fixed 80-column ASCII form")]
    Binary,
    /// A file without line breaks whose length is not a multiple of 80.
    #[error("line 1: {columns} columns without a line break (records are 80 columns)")]
    NoLineBreaks {
        /// The file's length.
        columns: usize,
    },
    /// A line longer than 80 columns with more than blanks past column 80.
    #[error("line {line}: {columns} columns (records are 80 columns)")]
    LongLine {
        /// The line.
        line: usize,
        /// Its length.
        columns: usize,
    },
    /// A line too short to hold a section letter.
    #[error(
        "line {line}: {} ({columns} columns, no section letter in column 73)",
        if *last { "the file is truncated" } else { "not an IGES record" }
    )]
    NoSectionLetter {
        /// The line.
        line: usize,
        /// Its length.
        columns: usize,
        /// Whether it is the file's last line (then the file is truncated).
        last: bool,
    },
    /// A section letter other than S, G, D, P, T.
    #[error(
        "line {line}: unknown section letter {letter:?} in column 73 (expected S, G, D, P or T)"
    )]
    UnknownSection {
        /// The line.
        line: usize,
        /// The letter found.
        letter: char,
    },
    /// Sections out of order.
    #[error("line {line}: section {found} after section {after} (the order is S, G, D, P, T)")]
    SectionOrder {
        /// The line.
        line: usize,
        /// The section of this line.
        found: char,
        /// The section before it.
        after: char,
    },
    /// Columns 74-80 that are not a number.
    #[error("line {line}: bad sequence number {text:?} in columns 74-80")]
    BadSequence {
        /// The line.
        line: usize,
        /// Columns 74-80.
        text: String,
    },
    /// A record numbered out of sequence.
    #[error("line {line}: {section} record numbered {found}, expected {expected}")]
    Sequence {
        /// The line.
        line: usize,
        /// Its section.
        section: char,
        /// Its number.
        found: usize,
        /// The number it should have.
        expected: usize,
    },
    /// More than one terminate record.
    #[error("line {line}: a second terminate (T) record")]
    SecondTerminate {
        /// The line.
        line: usize,
    },
    /// No global section.
    #[error("no global (G) section: not an IGES file, or truncated")]
    NoGlobal,
    /// No terminate record.
    #[error("no terminate (T) record: the file is truncated")]
    NoTerminate,
    /// An odd number of directory records.
    #[error("line {line}: odd number of directory (D) records ({count}); each entity has two")]
    OddDirectory {
        /// The last directory line.
        line: usize,
        /// The number of directory records.
        count: usize,
    },
    /// A directory field that is not an integer.
    #[error("line {line}: directory field {field} ({name}) {text:?} is not an integer")]
    DirectoryField {
        /// The line.
        line: usize,
        /// The field (1 to 9).
        field: usize,
        /// What the field is.
        name: &'static str,
        /// Its text.
        text: String,
    },
    /// A status number that is not eight digits.
    #[error("line {line}: status number {text:?} is not eight digits")]
    StatusNumber {
        /// The line.
        line: usize,
        /// Columns 65-72.
        text: String,
    },
    /// The two records of a directory entry disagree on the entity type.
    #[error(
        "line {line}: DE {de}: entity type {first} on the first record, {second} on the second"
    )]
    EntityTypes {
        /// The second record's line.
        line: usize,
        /// The entry.
        de: usize,
        /// The first record's type.
        first: i64,
        /// The second record's type.
        second: i64,
    },
    /// A delimiter definition that cannot be used.
    #[error("global section: {which} delimiter {found:?} is not usable")]
    Delimiter {
        /// `parameter` or `record`.
        which: &'static str,
        /// The character defined.
        found: char,
    },
    /// The same character for both delimiters.
    #[error("global section: the parameter and record delimiters are the same")]
    SameDelimiters,
    /// Something other than a delimiter after the global section's first field.
    #[error("global section: expected the parameter delimiter after field 1, found {found:?}")]
    AfterFirstGlobal {
        /// What follows the first field (`None`: the end).
        found: Option<char>,
    },

    // --- entities --------------------------------------------------------------------------
    /// A field of a parameter record (or of the global section, `who = "global section"`).
    #[error("{who}: parameter {index}{}: {problem}", field_name(name))]
    Field {
        /// The record's entity (`DE 57 (126 rational B-spline curve)`).
        who: String,
        /// The field's index in the record (1-based; the entity type is field 1).
        index: usize,
        /// What the field is (empty when unnamed).
        name: &'static str,
        /// What is wrong with it.
        problem: FieldProblem,
    },
    /// A null pointer where an entity is required.
    #[error("{from}: the pointer is 0 (no entity)")]
    NullPointer {
        /// Who points (`DE 5 (142 curve on a parametric surface): parameter-space curve`).
        from: String,
    },
    /// A pointer that is not the sequence number of a directory entry.
    #[error(
        "{from}: pointer {pointer} is not a directory entry (odd sequence numbers 1 to {})",
        2 * entries
    )]
    BadPointer {
        /// Who points.
        from: String,
        /// The pointer.
        pointer: usize,
        /// How many entries the directory has.
        entries: usize,
    },
    /// A directory entry's parameter data pointer or line count outside the parameter section.
    #[error(
        "{who}: parameter data at line {start} with {lines} lines {} (lines 1 to {available})",
        if *past_end { "runs past the end of the parameter section" } else { "is not in the parameter section" }
    )]
    ParameterLines {
        /// The entity.
        who: String,
        /// Its first parameter line.
        start: i64,
        /// Its line count.
        lines: i64,
        /// The parameter section's line count.
        available: usize,
        /// Whether the lines start inside the section but run past its end.
        past_end: bool,
    },
    /// A parameter line whose back pointer names another entry.
    #[error("{who}: parameter line {line} (file line {file_line}) belongs to DE {owner}")]
    ParameterOwner {
        /// The entity.
        who: String,
        /// The parameter line.
        line: usize,
        /// Its line in the file.
        file_line: usize,
        /// The back pointer written there.
        owner: String,
    },
    /// The work limit of the file is spent (entities referencing each other too often).
    #[error("{who}: the file's entities reference each other too many times (work limit reached)")]
    WorkLimit {
        /// The entity being read when the limit was reached.
        who: String,
    },
    /// A parameter record starting with another entity type than its directory entry's.
    #[error("{who}: its parameter data is of entity type {kind}")]
    ParameterType {
        /// The entity.
        who: String,
        /// The type in the parameter record.
        kind: i64,
    },
    /// A pointer to an entity of the wrong type.
    #[error("{from}: DE {de} is a {kind} {}, not {expected}", super::type_name(*kind))]
    WrongType {
        /// Who points.
        from: String,
        /// The entity pointed to.
        de: usize,
        /// Its type.
        kind: i64,
        /// What was expected.
        expected: &'static str,
    },
    /// Composite curves (or surfaces, groups, shells) containing each other.
    #[error("{who}: {what} contain each other (a cycle through DE {de})")]
    Cycle {
        /// The entity where the cycle closes.
        who: String,
        /// What contains what (`composite curves`, `surfaces`).
        what: &'static str,
        /// The entry met again.
        de: usize,
    },
    /// Nesting beyond [`super::MAX_DEPTH`].
    #[error("{who}: {what} nested deeper than {}", super::MAX_DEPTH)]
    TooDeep {
        /// The entity.
        who: String,
        /// What is nested.
        what: &'static str,
    },
    /// A cycle of transformation matrices.
    #[error("{who}: its transformation matrices form a cycle (DE {de} again)")]
    TransformCycle {
        /// The entity whose chain it is.
        who: String,
        /// The matrix met again.
        de: usize,
    },
    /// A chain of more than [`super::MAX_DEPTH`] transformation matrices.
    #[error(
        "{who}: a chain of more than {} transformation matrices",
        super::MAX_DEPTH
    )]
    TransformChain {
        /// The entity whose chain it is.
        who: String,
    },
    /// A negative transformation matrix pointer in a directory entry.
    #[error("{who}: negative transformation matrix pointer {pointer}")]
    NegativeTransform {
        /// The entity.
        who: String,
        /// The pointer.
        pointer: i64,
    },
    /// A form number the reader does not read for this entity.
    #[error("{who}: form {form} {what}")]
    Form {
        /// The entity.
        who: String,
        /// Its form.
        form: i64,
        /// Why (`is a ray, not a segment`).
        what: &'static str,
    },
    /// A flag with a value outside its set.
    #[error("{who}: {name} {value} (expected {expected})")]
    Flag {
        /// The entity.
        who: String,
        /// The flag (`N1`, `OF`).
        name: String,
        /// Its value.
        value: i64,
        /// The values allowed.
        expected: &'static str,
    },
    /// Geometry the data describes that cannot be built (degenerate axes, a zero radius, ...).
    #[error("{who}: {source}")]
    Geometry {
        /// The entity.
        who: String,
        /// Why.
        source: GeomError,
    },
    /// A curve the spline layer refuses (knots, weights, coordinates).
    #[error("{who}: {source}")]
    Spline {
        /// The entity.
        who: String,
        /// Why.
        source: SplineError,
    },
    /// A circular arc whose start point is its centre.
    #[error("{who}: the start point is the centre (radius 0)")]
    ZeroRadius {
        /// The 100 entity.
        who: String,
    },
    /// A 126 that says it is polynomial with unequal weights.
    #[error("{who}: PROP3 says polynomial but the weights are not all equal")]
    NotPolynomial {
        /// The 126 entity.
        who: String,
    },
    /// A 126's parameter range outside its knot domain.
    #[error("{who}: parameter range [{v0}, {v1}] is not inside the knot domain [{a}, {b}]")]
    TrimRange {
        /// The 126 entity.
        who: String,
        /// `V0`.
        v0: f64,
        /// `V1`.
        v1: f64,
        /// The domain's start.
        a: f64,
        /// The domain's end.
        b: f64,
    },
    /// A surface's parameter range that is empty.
    #[error("{who}: empty parameter range [{u0}, {u1}] x [{v0}, {v1}]")]
    EmptyRange {
        /// The surface entity.
        who: String,
        /// `U0`.
        u0: f64,
        /// `U1`.
        u1: f64,
        /// `V0`.
        v0: f64,
        /// `V1`.
        v1: f64,
    },
    /// A face bounded by its surface's parameter range where that range is not finite.
    #[error(
        "{who}: the outer boundary is the surface's parameter range ({flag} = 0), which is not \
         bounded for a {kind} {}",
        super::type_name(*kind)
    )]
    NoNaturalBounds {
        /// The surface entity.
        who: String,
        /// The face's flag whose value 0 asks for it (`N1` or `OF`).
        flag: &'static str,
        /// The surface's type.
        kind: i64,
    },
    /// A model-space curve that does not lie on its plane.
    #[error(
        "{who}: a control point of the model-space curve is {distance:e} off the surface's plane \
         (tolerance {tolerance:e})"
    )]
    OffPlane {
        /// The curve entity.
        who: String,
        /// The distance.
        distance: f64,
        /// The tolerance.
        tolerance: f64,
    },
    /// Consecutive curves of a loop that do not meet.
    #[error(
        "DE {named}: pieces DE {first} and DE {second} are {gap:e} apart (tolerance {tolerance:e})"
    )]
    Gap {
        /// The loop's entity.
        named: usize,
        /// The curve that ends.
        first: usize,
        /// The curve that should start there.
        second: usize,
        /// How far apart they are in `(u, v)`.
        gap: f64,
        /// The tolerance.
        tolerance: f64,
    },
    /// A face, loop or boundary with nothing in it.
    #[error("{who}: no {what}")]
    Nothing {
        /// The entity.
        who: String,
        /// What it lacks (`loops`, `edges`, `boundaries`).
        what: &'static str,
    },
    /// An index past the end of a 504 edge list or 502 vertex list.
    #[error("{from}: {what} {index} of the {list_kind} list DE {list}, which has {count}")]
    ListIndex {
        /// Who indexes.
        from: String,
        /// `edge` or `vertex`.
        what: &'static str,
        /// The index (1-based).
        index: usize,
        /// `504 edge` or `502 vertex`.
        list_kind: &'static str,
        /// The list's entry.
        list: usize,
        /// How many items it has.
        count: usize,
    },
    /// A 108 plane whose normal is zero.
    #[error("{who}: the normal (A, B, C) is zero")]
    ZeroNormal {
        /// The 108 entity.
        who: String,
    },
    /// A surface of a kind the reader cannot build.
    #[error("{who}: not a surface this reader knows (108, 120, 122, 128, 140, 190 to 198)")]
    UnknownSurface {
        /// The entity.
        who: String,
    },
    /// A swept curve (generatrix, directrix) made of several pieces.
    #[error("{who}: a {what} of several pieces (a composite curve) is not supported")]
    CompositeSweep {
        /// The surface entity.
        who: String,
        /// `generatrix` or `directrix`.
        what: &'static str,
    },
}

/// ` (name)` for a named field, nothing otherwise.
fn field_name(name: &str) -> String {
    if name.is_empty() {
        String::new()
    } else {
        format!(" ({name})")
    }
}

impl IgesError {
    /// The error of `source` about the entity `who`.
    pub(super) fn geometry(who: &str, source: GeomError) -> IgesError {
        IgesError::Geometry {
            who: who.to_string(),
            source,
        }
    }

    /// The error of `source` about the entity `who`.
    pub(super) fn spline(who: &str, source: SplineError) -> IgesError {
        IgesError::Spline {
            who: who.to_string(),
            source,
        }
    }
}
