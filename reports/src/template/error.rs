//! What is wrong with a template, and where: the errors of loading, checking
//! and rendering a page.

use std::fmt;

use minijinja::machinery::Span;

use super::Page;

/// A position in a template: line, and column in characters (0 when unknown).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Location {
    /// 1-based line.
    pub line: usize,
    /// 1-based column, 0 when unknown.
    pub column: usize,
}

impl Location {
    pub(super) fn of(source: &str, span: Span) -> Self {
        Self {
            line: usize::from(span.start_line),
            column: column(source, span.start_offset as usize),
        }
    }
}

/// The 1-based column, in characters, of byte `offset` of `source`.
pub(super) fn column(source: &str, offset: usize) -> usize {
    let offset = offset.min(source.len());
    let line_start = source[..offset].rfind('\n').map_or(0, |i| i + 1);
    source[line_start..offset].chars().count() + 1
}

/// A template that cannot be used, and where.
#[derive(Debug)]
pub struct TemplateError {
    /// The file as messages show it (`DIR/report.html`).
    pub file: String,
    /// Where in it, when known.
    pub location: Option<Location>,
    /// What is wrong.
    pub kind: TemplateErrorKind,
}

impl fmt::Display for TemplateError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.location {
            Some(Location { line, column: 0 }) => write!(f, "{}:{line}: error: {}", self.file, self.kind),
            Some(Location { line, column }) => write!(f, "{}:{line}:{column}: error: {}", self.file, self.kind),
            None => write!(f, "{}: error: {}", self.file, self.kind),
        }
    }
}

impl std::error::Error for TemplateError {}

/// What a template calls by name.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Callee {
    /// `x|name`, `{% filter name %}`.
    Filter,
    /// `x is name`.
    Test,
    /// `name(…)`.
    Function,
}

impl fmt::Display for Callee {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::Filter => "filter",
            Self::Test => "test",
            Self::Function => "function",
        })
    }
}

/// What is wrong with a template.
#[derive(Debug, thiserror::Error)]
pub enum TemplateErrorKind {
    /// The page's file is not in the set.
    #[error(
        "no such file: a template set for `{}` holds `{}`, which may extend `{}`",
        .0.command(),
        .0.file(),
        .0.bundled()
    )]
    MissingPage(Page),
    /// A template names another that is not in the set.
    #[error("no such template: {0}")]
    NotFound(String),
    /// The file could not be read.
    #[error("{0}")]
    Unreadable(String),
    /// The template does not compile.
    #[error("{0}")]
    Syntax(String),
    /// `extends`, `include` or `import` names its template with an expression.
    #[error("name the template in quotes: the templates a page uses are checked before anything runs")]
    DynamicName,
    /// The extends chain comes back to a template.
    #[error("`{0}` extends this template again")]
    Cycle(String),
    /// A required block is not shown.
    #[error(
        "the page does not show required block `{block}`: a page of `{}` must show the blocks {} (extend `{}` to inherit them)",
        page.command(),
        page.required_blocks().join(", "),
        page.bundled()
    )]
    MissingBlock {
        /// The block.
        block: String,
        /// The page.
        page: Page,
    },
    /// A block the template defines is never shown.
    #[error(
        "block `{block}` is never shown: the page has no such block, or an override around it leaves it out (the page shows {})",
        shown.join(", ")
    )]
    NeverShown {
        /// The block.
        block: String,
        /// The blocks the page shows.
        shown: Vec<String>,
    },
    /// `autoescape` or `safe` would turn escaping off.
    #[error("`autoescape` and the `safe` filter are not available: report data is always HTML-escaped")]
    Unescaped,
    /// A template calls a filter, test or function there is no such one of.
    #[error("unknown {0}: `{1}` is none of this build's (see docs/report-templates.md)")]
    Unknown(Callee, String),
    /// Rendering failed (a misspelt field, a value of the wrong type…).
    #[error("failed to render the page: {0}")]
    Render(String),
}
