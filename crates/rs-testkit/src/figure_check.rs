//! What every figure a user sees must have, checked on its SVG text.

/// Asserts that `svg` is well-formed XML with a white background, axes (a frame with tick
/// labels), a legend naming at least one thing (or a colour bar), and a caption containing
/// `caption` (so a figure explains itself). `what` names the figure in failure messages.
///
/// # Panics
/// When any of these is missing.
pub fn assert_figure(svg: &str, caption: &str, what: &str) {
    let doc = roxmltree::Document::parse(svg)
        .unwrap_or_else(|e| panic!("{what}: not well-formed SVG: {e}"));
    assert!(
        doc.root_element().has_tag_name("svg"),
        "{what}: the root is not <svg>"
    );
    let group_text = |class: &str| -> String {
        doc.descendants()
            .filter(|n| n.attribute("class") == Some(class))
            .flat_map(|g| g.descendants().filter_map(|n| n.text()))
            .collect::<Vec<_>>()
            .join(" ")
    };
    let has_group = |class: &str| {
        doc.descendants()
            .any(|n| n.attribute("class") == Some(class))
    };
    assert!(has_group("axes"), "{what}: no axes");
    assert!(
        !group_text("axes").trim().is_empty(),
        "{what}: axes without tick labels"
    );
    let legend = group_text("legend");
    assert!(
        !legend.trim().is_empty() || has_group("colour-bar"),
        "{what}: no legend and no colour bar"
    );
    let text = group_text("caption");
    let text = text.split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(
        text.contains(caption),
        "{what}: the caption {text:?} does not contain {caption:?}"
    );
}
