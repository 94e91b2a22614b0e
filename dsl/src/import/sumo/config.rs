//! SUMO configuration files (`.sumocfg`): which network, route, additional and
//! FCD output files a simulation reads and writes.

use roxmltree::Node;

use super::xml::{self, SumoError};
use crate::Location;

/// The files a `.sumocfg` names, each as written (relative to the
/// configuration's directory unless absolute) with where it is written.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Config {
    /// The network (`net-file`).
    pub net: Option<ConfigFile>,
    /// The route files (`route-files`), in order.
    pub routes: Vec<ConfigFile>,
    /// The additional files (`additional-files`), in order.
    pub additional: Vec<ConfigFile>,
    /// The floating car data the simulation writes (`fcd-output`).
    pub fcd: Option<ConfigFile>,
}

/// A file a configuration names.
#[derive(Debug, Clone, PartialEq)]
pub struct ConfigFile {
    /// The path as written.
    pub path: String,
    /// Where the configuration writes it: the first character of the `value`.
    pub location: Location,
}

/// Each option the reader takes, with the names SUMO also accepts for it.
const NET: [&str; 2] = ["net-file", "net"];
const ROUTES: [&str; 2] = ["route-files", "routes"];
const ADDITIONAL: [&str; 2] = ["additional-files", "additional"];
const FCD: [&str; 1] = ["fcd-output"];

/// Reads a SUMO configuration (`<configuration><input><net-file value="…"/>…`).
///
/// Options are found by name in any section (SUMO ignores the section names),
/// each with its `value`; file lists are separated by commas or spaces, as SUMO
/// reads them. Other options are ignored: they change how SUMO simulates, which
/// the FCD output already holds.
///
/// Errors: malformed XML, a root other than `<configuration>` (or
/// `<sumoConfiguration>`, which SUMO writes), an option without `value`, and an
/// option given twice.
pub fn parse_config(text: &str) -> Result<Config, SumoError> {
    let doc = xml::parse(text)?;
    let root = doc.root_element();
    if !matches!(root.tag_name().name(), "configuration" | "sumoConfiguration") {
        return Err(xml::element_error(
            root,
            format!("expected <configuration> as the root element, found {}", xml::tag(root)),
        ));
    }
    let mut config = Config::default();
    let mut seen: Vec<(&str, Node)> = Vec::new();
    // Options sit in sections (`<input>`) or, less often, right under the root.
    let options = root
        .children()
        .filter(Node::is_element)
        .flat_map(|section| std::iter::once(section).chain(section.children().filter(Node::is_element)));
    for option in options {
        let name = option.tag_name().name();
        let Some(canonical) = [&NET[..], &ROUTES, &ADDITIONAL, &FCD]
            .into_iter()
            .find(|names| names.contains(&name))
            .map(|names| names[0])
        else {
            continue;
        };
        if let Some((_, first)) = seen.iter().find(|(seen, _)| *seen == canonical) {
            let line = first.document().text_pos_at(first.range().start).row;
            return Err(xml::element_error(
                option,
                format!("option `{canonical}` is given twice (first on line {line})"),
            ));
        }
        seen.push((canonical, option));
        let files = files(option)?;
        match canonical {
            "net-file" => config.net = one(option, files)?,
            "route-files" => config.routes = files,
            "additional-files" => config.additional = files,
            _ => config.fcd = one(option, files)?,
        }
    }
    Ok(config)
}

/// The files of an option's `value`, each located at its first character.
fn files(option: Node) -> Result<Vec<ConfigFile>, SumoError> {
    let attribute = xml::attribute(option, "value")?;
    let value = attribute.value();
    let raw = &option.document().input_text()[attribute.range_value()];
    let start = attribute.range_value().start;
    Ok(value
        .split(|c: char| c == ',' || c.is_ascii_whitespace())
        .filter(|token| !token.is_empty())
        .map(|token| {
            // Exact only without entity references in the value, as for shapes.
            let offset = token.as_ptr() as usize - value.as_ptr() as usize;
            let pos = if raw == value { start + offset } else { start };
            let pos = option.document().text_pos_at(pos);
            ConfigFile {
                path: token.to_owned(),
                location: Location::new(pos.row as usize, pos.col as usize),
            }
        })
        .collect())
}

/// The one file of an option that takes one.
fn one(option: Node, mut files: Vec<ConfigFile>) -> Result<Option<ConfigFile>, SumoError> {
    if files.len() > 1 {
        let attribute = xml::attribute(option, "value")?;
        let message = format!(
            "option `{}` names {} files; it takes one",
            option.tag_name().name(),
            files.len()
        );
        return Err(xml::value_error(option, &attribute, message));
    }
    Ok(files.pop())
}

#[cfg(test)]
mod tests {
    use super::*;

    const CONFIG: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<configuration xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance">
    <input>
        <net-file value="town.net.xml"/>
        <route-files value="vtypes.add.xml,town.rou.xml"/>
        <additional-files value="town.poly.xml  pois.add.xml"/>
    </input>
    <time><begin value="0"/><end value="90"/></time>
    <output>
        <fcd-output value="out/town.fcd.xml"/>
        <fcd-output.attributes value="x,y,angle,type,speed,lane"/>
    </output>
</configuration>
"#;

    fn paths(files: &[ConfigFile]) -> Vec<(&str, String)> {
        files
            .iter()
            .map(|f| (f.path.as_str(), f.location.to_string()))
            .collect()
    }

    #[test]
    fn reads_the_files_with_where_they_are_written() {
        let config = parse_config(CONFIG).unwrap();
        let net = config.net.unwrap();
        assert_eq!(
            (net.path.as_str(), net.location),
            ("town.net.xml", Location::new(4, 26))
        );
        assert_eq!(
            paths(&config.routes),
            [
                ("vtypes.add.xml", "5:29".to_string()),
                ("town.rou.xml", "5:44".to_string())
            ]
        );
        assert_eq!(
            paths(&config.additional),
            [
                ("town.poly.xml", "6:34".to_string()),
                ("pois.add.xml", "6:49".to_string())
            ]
        );
        assert_eq!(config.fcd.unwrap().path, "out/town.fcd.xml");
    }

    #[test]
    fn options_outside_sections_and_short_names_are_read() {
        let config = parse_config(
            r#"<sumoConfiguration><net value="a.net.xml"/><routes value="b.rou.xml"/></sumoConfiguration>"#,
        )
        .unwrap();
        assert_eq!(config.net.unwrap().path, "a.net.xml");
        assert_eq!(paths(&config.routes), [("b.rou.xml", "1:59".to_string())]);
        assert_eq!(config.fcd, None);
    }

    #[test]
    fn errors_are_located() {
        let error = |text: &str| parse_config(text).unwrap_err().to_string();
        assert_eq!(
            error("<net/>"),
            "1:1: expected <configuration> as the root element, found <net>"
        );
        assert_eq!(
            error("<configuration>\n<input><net-file/></input></configuration>"),
            "2:8: missing attribute `value` on <net-file>"
        );
        assert_eq!(
            error("<configuration>\n<input><net-file value=\"a b\"/></input></configuration>"),
            "2:25: option `net-file` names 2 files; it takes one"
        );
        assert_eq!(
            error("<configuration><input><net-file value=\"a\"/>\n<net value=\"b\"/></input></configuration>"),
            "2:1: option `net-file` is given twice (first on line 1)"
        );
    }
}
