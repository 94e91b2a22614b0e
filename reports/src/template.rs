//! Page templates: the bundled set, and an organisation's own (`--template DIR`).
//!
//! The pages are minijinja templates. The bundled ones are embedded under
//! stable names: `sightline/page.html` (the layout: `head` with `title` and
//! `style`, then `header`, `content` and `footer`), the document-control and
//! provenance tables both pages include (`sightline/control.html`,
//! `sightline/provenance.html`), the macros they import
//! (`sightline/macros.html`), and the two pages that extend
//! it, `sightline/report.html` (`sightline run`) and
//! `sightline/falsify.html` (`sightline falsify`). A custom set is a directory
//! holding `report.html` and/or `falsify.html` and whatever they include or
//! extend; a page may extend its bundled page and override some blocks, or
//! stand alone.
//!
//! A custom set is checked when it is loaded, before anything is simulated:
//! every template it reaches by name compiles; the page shows every block its
//! contract requires ([`Page::required_blocks`]), defined or inherited; every
//! block a custom template defines is shown (an override of a block the page
//! does not have, or one dropped by an override around it, would silently
//! vanish); nothing turns escaping off; and every filter, test and function it
//! calls exists. Every template is HTML-escaped whatever its file name;
//! `autoescape` blocks and the `safe` filter are not available, and the
//! filters that make text return plain text, never markup ([`text`]). What
//! cannot be known before the data exists (a misspelt field) is an error when
//! the page is rendered.
//!
//! This module loads a set into its environment and renders a page; the check
//! is in [`check`], the errors in [`error`].

use std::fmt;
use std::sync::Arc;

use minijinja::value::Serde;
use minijinja::{AutoEscape, Environment, ErrorKind, UndefinedBehavior, Value, context};
use serde::Serialize;

use error::column;
pub use error::{Callee, Location, TemplateError, TemplateErrorKind};

mod check;
mod error;
mod text;

/// The bundled templates, by their stable names.
const BUNDLED: [(&str, &str); 6] = [
    ("sightline/page.html", include_str!("../templates/page.html")),
    ("sightline/control.html", include_str!("../templates/control.html")),
    (
        "sightline/provenance.html",
        include_str!("../templates/provenance.html"),
    ),
    ("sightline/macros.html", include_str!("../templates/macros.html")),
    ("sightline/report.html", include_str!("../templates/report.html")),
    ("sightline/falsify.html", include_str!("../templates/falsify.html")),
];

/// The prefix of the bundled templates' names; a custom set cannot shadow them.
const BUNDLED_PREFIX: &str = "sightline/";

/// A page sightline renders from a template.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Page {
    /// `report.html` of `sightline run`.
    Run,
    /// `report.html` of `sightline falsify`.
    Falsify,
}

impl Page {
    /// The file a custom set holds for this page.
    pub fn file(self) -> &'static str {
        match self {
            Self::Run => "report.html",
            Self::Falsify => "falsify.html",
        }
    }

    /// The bundled template's stable name, for `{% extends %}`.
    pub fn bundled(self) -> &'static str {
        match self {
            Self::Run => "sightline/report.html",
            Self::Falsify => "sightline/falsify.html",
        }
    }

    /// The blocks a template of this page must show: what makes the page
    /// evidence (its document control, the verdict, the scope, what the
    /// models assumed, the provenance, what was checked and found, the tool's
    /// self-test and the scenario file).
    pub fn required_blocks(self) -> &'static [&'static str] {
        match self {
            Self::Run => &[
                "document_control",
                "banner",
                "scope",
                "assumptions",
                "provenance",
                "traceability",
                "evidence",
                "selftest",
                "appendix",
            ],
            Self::Falsify => &[
                "document_control",
                "banner",
                "provenance",
                "settings",
                "cases",
                "counterexample",
                "requirements",
            ],
        }
    }

    /// The command whose page this is, for messages.
    fn command(self) -> &'static str {
        match self {
            Self::Run => "sightline run",
            Self::Falsify => "sightline falsify",
        }
    }
}

/// Reads a template of a custom set by name (`report.html`, `parts/head.html`):
/// `Ok(None)` when there is no such file.
pub type Loader = dyn Fn(&str) -> std::io::Result<Option<String>> + Send + Sync;

/// The templates a page is rendered with: the bundled ones, or a checked
/// custom set (with the bundled ones under their stable names).
pub struct Templates {
    env: Environment<'static>,
    page: Page,
    /// The custom set's directory as messages show it, if any.
    dir: Option<String>,
}

impl fmt::Debug for Templates {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Templates")
            .field("page", &self.page)
            .field("dir", &self.dir)
            .finish_non_exhaustive()
    }
}

impl Templates {
    /// The bundled template of `page`.
    pub fn bundled(page: Page) -> Self {
        Self {
            env: environment(None),
            page,
            dir: None,
        }
    }

    /// The custom set in `dir` (as messages show it), read through `load`,
    /// checked for `page` (see the module documentation).
    pub fn custom(page: Page, dir: &str, load: Arc<Loader>) -> Result<Self, TemplateError> {
        let templates = Self {
            env: environment(Some(load)),
            page,
            dir: Some(dir.to_string()),
        };
        templates.check()?;
        Ok(templates)
    }

    /// Whether this is a custom set (so a failure to render is the input's).
    pub fn is_custom(&self) -> bool {
        self.dir.is_some()
    }

    /// Renders the page with `report` (the page's view) and `results` (the
    /// document written beside it: results.json or falsify.json).
    pub(crate) fn render(&self, report: &impl Serialize, results: &impl Serialize) -> Result<String, TemplateError> {
        let name = self.entry();
        let template = self.env.get_template(name).map_err(|e| self.error(name, &e))?;
        template
            .render(context! {
                report => Value::from(Serde(report)),
                results => Value::from(Serde(results)),
            })
            .map_err(|e| self.error(name, &e))
    }

    /// The template rendered for the page.
    fn entry(&self) -> &'static str {
        if self.is_custom() {
            self.page.file()
        } else {
            self.page.bundled()
        }
    }

    /// A template's name as messages show it: in the custom set's directory,
    /// or as the bundled name.
    fn display(&self, name: &str) -> String {
        match &self.dir {
            Some(dir) if !name.starts_with(BUNDLED_PREFIX) => format!("{}/{name}", dir.trim_end_matches('/')),
            _ => name.to_string(),
        }
    }

    /// A minijinja error of template `name` (or of the template it names itself).
    fn error(&self, name: &str, error: &minijinja::Error) -> TemplateError {
        let location = error.line().map(|line| Location {
            line,
            column: match (error.range(), error.template_source()) {
                (Some(range), Some(source)) => column(source, range.start),
                _ => 0,
            },
        });
        let message = match error.detail() {
            Some(detail) => format!("{}: {detail}", error.kind()),
            None => error.kind().to_string(),
        };
        let kind = match error.kind() {
            ErrorKind::SyntaxError => TemplateErrorKind::Syntax(message),
            // What the loader could not read (it says so).
            ErrorKind::InvalidOperation if location.is_none() => {
                TemplateErrorKind::Unreadable(error.detail().unwrap_or(&message).to_string())
            }
            _ => TemplateErrorKind::Render(message),
        };
        TemplateError {
            file: self.display(error.name().unwrap_or(name)),
            location,
            kind,
        }
    }
}

/// The work a custom set may do to render one page, in minijinja's fuel (about
/// one instruction, or 64 bytes of data): a bound on the time and memory a
/// template's loops can take (the worst pages measured stay within 1.2 GB
/// and 1.5 s of CPU, docs/report-templates.md). The example set renders
/// the page of every bundled scenario within it.
const CUSTOM_FUEL: u64 = 20_000_000;

/// The environment every page renders in: strict about undefined values,
/// escaping every template as HTML, the bundled templates under their names
/// and, with `load`, a custom set's files under theirs, rendered on at most
/// [`CUSTOM_FUEL`].
fn environment(load: Option<Arc<Loader>>) -> Environment<'static> {
    let mut env = Environment::new();
    if load.is_some() {
        env.set_fuel(Some(CUSTOM_FUEL));
        env.set_formatter(text::affordable);
    }
    // Minijinja's default follows the build (on only with debug assertions,
    // so in every test build): a release build's render errors would lose
    // their column and what was undefined.
    env.set_debug(true);
    env.set_undefined_behavior(UndefinedBehavior::Strict);
    // Escaping follows the name's extension by default; a custom set's
    // `header.txt` must be escaped too.
    env.set_auto_escape_callback(|_| AutoEscape::Html);
    env.remove_filter("safe");
    text::register(&mut env);
    env.set_loader(move |name| {
        if let Some((_, source)) = BUNDLED.iter().find(|(bundled, _)| *bundled == name) {
            return Ok(Some((*source).to_string()));
        }
        let Some(load) = load.as_ref().filter(|_| is_plain(name)) else {
            return Ok(None);
        };
        load(name).map_err(|error| {
            minijinja::Error::new(
                ErrorKind::InvalidOperation,
                format!("failed to read the template: {error}"),
            )
        })
    });
    env
}

/// Whether `name` may be read from a custom set: relative, `/`-separated, no
/// segment starting with a dot (no `..`, no hidden files), outside `sightline/`.
fn is_plain(name: &str) -> bool {
    !name.starts_with(BUNDLED_PREFIX)
        && name
            .split('/')
            .all(|segment| !segment.is_empty() && !segment.starts_with('.') && !segment.contains('\\'))
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeMap;

    use super::*;

    /// A custom set in directory `org` holding `files`.
    fn custom(page: Page, files: &[(&str, &str)]) -> Result<Templates, TemplateError> {
        let files: BTreeMap<String, String> = files.iter().map(|(n, t)| (n.to_string(), t.to_string())).collect();
        Templates::custom(page, "org", Arc::new(move |name: &str| Ok(files.get(name).cloned())))
    }

    /// The error's message, as the CLI prints it.
    fn refused(page: Page, files: &[(&str, &str)]) -> String {
        custom(page, files).expect_err("the set is refused").to_string()
    }

    #[test]
    fn the_bundled_pages_show_their_blocks() {
        let blocks = |page| Vec::from_iter(Templates::bundled(page).blocks().unwrap());
        let layout = ["content", "footer", "head", "header", "style", "title"];
        let run = [
            "appendix",
            "argument",
            "assumptions",
            "banner",
            "comparison",
            "description",
            "details",
            "document_control",
            "evidence",
            "pictures",
            "provenance",
            "scope",
            "selftest",
            "sweeps",
            "traceability",
        ];
        let falsify = [
            "banner",
            "cases",
            "chart",
            "counterexample",
            "document_control",
            "provenance",
            "requirements",
            "settings",
        ];
        let sorted = |page: &[&str]| {
            let mut all: Vec<String> = layout.iter().chain(page).map(|b| b.to_string()).collect();
            all.sort();
            all
        };
        assert_eq!(blocks(Page::Run), sorted(&run));
        assert_eq!(blocks(Page::Falsify), sorted(&falsify));
        for page in [Page::Run, Page::Falsify] {
            let shown = Templates::bundled(page).blocks().unwrap();
            assert!(page.required_blocks().iter().all(|b| shown.contains(*b)), "{page:?}");
        }
    }

    #[test]
    fn a_page_that_extends_the_bundled_one_may_override_any_block() {
        let set = custom(
            Page::Run,
            &[
                (
                    "report.html",
                    r#"{% extends "sightline/report.html" %}
{% block style %}{{ super() }} h1 { color: navy; }{% endblock %}
{% block pictures %}<p>no pictures</p>{% endblock %}
{% block footer %}{% include "parts/footer.txt" %}{% endblock %}"#,
                ),
                ("parts/footer.txt", "ACME Safety"),
            ],
        )
        .unwrap();
        assert!(set.is_custom());
        assert!(set.blocks().unwrap().contains("pictures"));
        // A standalone page only has to show the required blocks.
        custom(
            Page::Falsify,
            &[(
                "falsify.html",
                "{% block document_control %}{% endblock %}{% block banner %}{% endblock %}{% block provenance %}{% endblock %}\
                 {% for c in report.cases %}{% block cases %}{{ c }}{% endblock %}{% endfor %}\
                 {% if report.counterexample %}{% block counterexample %}{% endblock %}{% endif %}\
                 {% block settings %}{% endblock %}{% block requirements %}{% endblock %}",
            )],
        )
        .unwrap();
    }

    #[test]
    fn a_missing_page_or_template_is_named() {
        let message = refused(Page::Run, &[("falsify.html", "x")]);
        assert!(
            message.starts_with(
                "org/report.html: error: no such file: a template set for `sightline run` holds `report.html`"
            ),
            "{message}"
        );
        let message = refused(
            Page::Run,
            &[(
                "report.html",
                "{% extends \"sightline/report.html\" %}\n{% block footer %}{% include \"gone.html\" %}{% endblock %}",
            )],
        );
        assert_eq!(message, "org/report.html:2:22: error: no such template: org/gone.html");
        // `ignore missing` is honoured; names outside the set are never read.
        custom(
            Page::Run,
            &[("report.html", "{% extends \"sightline/report.html\" %}{% block footer %}{% include \"gone.html\" ignore missing %}{% endblock %}")],
        )
        .unwrap();
        let message = refused(Page::Run, &[("report.html", "{% extends \"../report.html\" %}")]);
        assert!(message.contains("no such template: org/../report.html"), "{message}");
    }

    #[test]
    fn a_template_that_cannot_be_read_is_named() {
        let load = |_: &str| Err(std::io::Error::new(std::io::ErrorKind::PermissionDenied, "denied"));
        let error = Templates::custom(Page::Run, "org", Arc::new(load)).unwrap_err();
        assert_eq!(
            error.to_string(),
            "org/report.html: error: failed to read the template: denied"
        );
    }

    #[test]
    fn syntax_errors_name_the_file_line_and_column() {
        let message = refused(
            Page::Run,
            &[("report.html", "<p>\n{% if report.name %}\n  {% endfor %}")],
        );
        assert_eq!(
            message,
            "org/report.html:3:6: error: syntax error: unknown statement endfor"
        );
        // In an included template, the included file is named.
        let message = refused(
            Page::Run,
            &[
                (
                    "report.html",
                    "{% extends \"sightline/report.html\" %}{% block footer %}{% include \"f.html\" %}{% endblock %}",
                ),
                ("f.html", "ok\n{{ report.name "),
            ],
        );
        assert!(message.starts_with("org/f.html:2:"), "{message}");
        assert!(message.contains("syntax error"), "{message}");
    }

    #[test]
    fn a_required_block_that_is_not_shown_is_refused() {
        let message = refused(Page::Run, &[("report.html", "{% block banner %}{% endblock %}")]);
        assert_eq!(
            message,
            "org/report.html: error: the page does not show required block `document_control`: a page of `sightline run` \
             must show the blocks document_control, banner, scope, assumptions, provenance, traceability, evidence, \
             selftest, appendix (extend `sightline/report.html` to inherit them)"
        );
        // Overriding the block that holds it hides it too.
        let message = refused(
            Page::Run,
            &[(
                "report.html",
                "{% extends \"sightline/report.html\" %}{% block content %}{% block banner %}{% endblock %}{% endblock %}",
            )],
        );
        assert!(
            message.contains("does not show required block `document_control`"),
            "{message}"
        );
        // Unless the override shows its parent's body.
        custom(
            Page::Run,
            &[(
                "report.html",
                "{% extends \"sightline/report.html\" %}{% block content %}<div>{{ super() }}</div>{% endblock %}",
            )],
        )
        .unwrap();
    }

    #[test]
    fn a_block_that_would_never_be_shown_is_refused() {
        let message = refused(
            Page::Run,
            &[(
                "report.html",
                "{% extends \"sightline/report.html\" %}\n\n{% block provenence %}x{% endblock %}",
            )],
        );
        assert!(
            message.starts_with(
                "org/report.html:3:4: error: block `provenence` is never shown: the page has no such block"
            ),
            "{message}"
        );
        assert!(
            message.contains("argument, assumptions, banner, comparison"),
            "{message}"
        );
        // An override of `details` that leaves `pictures` out hides an override of `pictures`.
        let message = refused(
            Page::Run,
            &[(
                "report.html",
                "{% extends \"sightline/report.html\" %}{% block details %}none{% endblock %}{% block pictures %}x{% endblock %}",
            )],
        );
        assert!(message.contains("block `pictures` is never shown"), "{message}");
    }

    #[test]
    fn escaping_cannot_be_turned_off() {
        for source in [
            "{% block x %}{{ report.name|safe }}{% endblock %}",
            "{% block x %}{{ report.name | safe }}{% endblock %}",
            "{% autoescape false %}{{ report.name }}{% endautoescape %}",
            "{% filter safe %}{{ report.name }}{% endfilter %}",
        ] {
            let page = format!("{{% extends \"sightline/report.html\" %}}{source}");
            let message = refused(Page::Run, &[("report.html", &page)]);
            assert!(
                message.contains("`autoescape` and the `safe` filter are not available"),
                "{source}: {message}"
            );
        }
        // Whatever a template's name, what it shows is escaped.
        let set = custom(
            Page::Falsify,
            &[(
                "falsify.html",
                "{% block document_control %}{% endblock %}{% block banner %}{% include \"name.txt\" %}{% endblock %}{% block provenance %}{% endblock %}\
                 {% block settings %}{% endblock %}{% block cases %}{% endblock %}{% block counterexample %}{% endblock %}{% block requirements %}{% endblock %}",
            ), ("name.txt", "{{ report.name }}")],
        )
        .unwrap();
        let html = set
            .render(&serde_json::json!({ "name": "<script>x</script>" }), &())
            .unwrap();
        assert_eq!(html, "&lt;script&gt;x&lt;&#x2f;script&gt;");
    }

    /// `body` rendered in a standalone page of `sightline falsify`, with
    /// `report.name` set to `name`.
    fn rendered(body: &str, name: &str) -> Result<String, TemplateError> {
        let page = format!(
            "{{% block document_control %}}{{% endblock %}}{{% block banner %}}{body}{{% endblock %}}\
             {{% block provenance %}}{{% endblock %}}{{% block settings %}}{{% endblock %}}{{% block cases %}}{{% endblock %}}\
             {{% block counterexample %}}{{% endblock %}}{{% block requirements %}}{{% endblock %}}"
        );
        custom(Page::Falsify, &[("falsify.html", &page)])?.render(&serde_json::json!({ "name": name }), &())
    }

    #[test]
    fn no_filter_turns_a_values_escaped_text_into_markup() {
        // Markup the template writes, captured whole, stays markup: `s` holds
        // the name escaped, `lt` a `<`.
        let set = "{% set lt %}<{% endset %}{% set s %}{{ report.name }}{% endset %}";
        let name = "<script>x</script>";
        for attack in [
            // The audit's: a markup `to` spliced into the escaped name.
            r#"{{ report.name|replace("&lt;", lt) }}"#,
            r#"{{ s|replace("&lt;", "<") }}"#,
            r#"{{ report.name|e|replace("&lt;", lt) }}"#,
            r#"{{ report.name|escape|replace("&lt;", "<", 5) }}"#,
            r#"{% filter replace("&lt;", lt) %}{{ report.name }}{% endfilter %}"#,
            r#"{% macro m() %}{{ report.name }}{% endmacro %}{{ m()|replace("&lt;", lt) }}"#,
            r#"{% macro w() %}{{ caller()|replace("&lt;", lt) }}{% endmacro %}{% call w() %}{{ report.name }}{% endcall %}"#,
            // Cut the escaped text at its entities and put markup between the pieces.
            r#"{{ s|split("&lt;")|join(lt) }}"#,
            r#"{{ s|split("&lt;")|join(d=lt) }}"#,
            r#"{% set p = s|lines|first %}{{ p|replace("&lt;", lt) }}"#,
            r#"{{ [s, lt]|join|replace("&lt;", lt) }}"#,
            r#"{{ s|format|replace("&lt;", lt) }}"#,
            r#"{{ "%s"|format(s)|replace("&lt;", lt) }}"#,
            r#"{{ s|indent(2)|trim|lower|upper|capitalize|reverse|reverse|replace("&lt;", lt) }}"#,
            r#"{{ (s|string)|replace("&lt;", lt) }}"#,
            r#"{{ (s ~ lt)|replace("&lt;", lt) }}"#,
            r#"{{ (s * 2)|replace("&lt;", lt) }}"#,
        ] {
            let html = rendered(&format!("{set}{attack}"), name).unwrap_or_else(|e| panic!("{attack}: {e}"));
            assert!(!html.contains('<'), "{attack} shows markup made of the name: {html}");
            assert!(html.contains("lt;script"), "{attack}: {html}");
        }
        // The template's own markup, captured, is kept; a filter reads it as text.
        let html = rendered(
            r#"{% set b %}<b>{{ report.name }}</b>{% endset %}{{ b }} {{ b ~ "<i>" }} {{ report.name|e }} {{ b|upper }}"#,
            "<x>",
        )
        .unwrap();
        assert_eq!(
            html,
            "<b>&lt;x&gt;</b> <b>&lt;x&gt;</b>&lt;i&gt; &lt;x&gt; &lt;B&gt;&amp;LT;X&amp;GT;&lt;&#x2f;B&gt;"
        );
        // The filters still do their work on plain text.
        let html = rendered(
            r#"{{ "a-b-a"|replace("a", "c") }} {{ "a-b-a"|replace("a", "c", 1) }} {{ "x\ny"|indent(2, true) }} {{ [1, 2]|join(", ") }} {{ "%03d"|format(7) }} {{ "ab"|reverse }}"#,
            "",
        )
        .unwrap();
        assert_eq!(html, "c-b-c c-b-a   x\n  y 1, 2 007 ba");
    }

    #[test]
    fn an_unknown_filter_test_or_function_is_refused_before_anything_runs() {
        for (body, at, message) in [
            ("{{ results|tojson(indent=2) }}", 12, "unknown filter: `tojson`"),
            ("{% filter shout %}x{% endfilter %}", 11, "unknown filter: `shout`"),
            (
                "{% if report.name is not palindrome %}x{% endif %}",
                26,
                "unknown test: `palindrome`",
            ),
            ("{{ now() }}", 4, "unknown function: `now`"),
        ] {
            let page = format!("{{% extends \"sightline/report.html\" %}}{{% block footer %}}\n{body}{{% endblock %}}");
            let message_of = refused(Page::Run, &[("report.html", &page)]);
            assert!(
                message_of.starts_with(&format!(
                    "org/report.html:2:{at}: error: {message} is none of this build's"
                )),
                "{body}: {message_of}"
            );
        }
        // Filters, tests and functions that exist; macros, imported names and
        // names given a value are called freely.
        custom(
            Page::Run,
            &[
                (
                    "report.html",
                    "{% extends \"sightline/report.html\" %}{% from \"m.html\" import shout %}{% import \"m.html\" as m %}\
                     {% block footer %}{% set f = shout %}{{ shout(report.name|upper) }}{{ m.shout(1) }}{{ f(2) }}\
                     {% for i in range(2) if i is odd and i is not none %}{{ dict(a=i)|length }}{% endfor %}\
                     {% filter lower %}X{% endfilter %}{% if not(report.name) %}{% endif %}{% endblock %}",
                ),
                ("m.html", "{% macro shout(x) %}{{ x }}!{% endmacro %}"),
            ],
        )
        .unwrap();
    }

    #[test]
    fn template_names_are_constants_and_extends_does_not_loop() {
        let message = refused(
            Page::Run,
            &[("report.html", "{% set base = \"a.html\" %}{% extends base %}")],
        );
        assert!(message.contains("error: name the template in quotes"), "{message}");
        let message = refused(
            Page::Run,
            &[
                ("report.html", "{% extends \"a.html\" %}"),
                ("a.html", "{% extends \"report.html\" %}"),
            ],
        );
        assert!(
            message.starts_with("org/a.html:1:4: error: `report.html` extends this template again"),
            "{message}"
        );
    }

    #[test]
    fn a_misspelt_field_fails_when_rendered_with_its_place() {
        let set = custom(
            Page::Falsify,
            &[(
                "falsify.html",
                "{% block document_control %}{% endblock %}{% block banner %}{% endblock %}{% block provenance %}{% endblock %}{% block settings %}{% endblock %}\
                 {% block cases %}{% endblock %}{% block requirements %}{% endblock %}\n{% block counterexample %}{{ report.nmae }}{% endblock %}",
            )],
        )
        .unwrap();
        let error = set.render(&serde_json::json!({ "name": "x" }), &()).unwrap_err();
        assert!(matches!(error.kind, TemplateErrorKind::Render(_)));
        assert!(error.to_string().starts_with("org/falsify.html:2:"), "{error}");
    }
}
