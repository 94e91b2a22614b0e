//! The check of a custom template set against its page, before anything
//! runs: the blocks the page shows (defined or inherited, and not hidden by an
//! override around them), the templates it reaches by name, what would turn
//! escaping off, and the filters, tests and functions it calls.
//!
//! It walks minijinja's syntax tree (`unstable_machinery`, pinned by
//! the workspace's minijinja version): blocks, `extends`, `include` and
//! `import` with constant names. `super()` is found by its text, so a block
//! that mentions it is taken to show its parent's body: the check may accept
//! a page that hides a block, never refuse one that shows it. The names a
//! template calls are read from its tokens: `x|name` and `{% filter name %}`
//! must be filters of the environment, `x is name` a test, and `name(…)` one
//! of its functions or a name some template of the page mentions otherwise
//! (a macro, an import, an assignment, a parameter). A filter named by a
//! string (`map("upper")`) is known only when it is called.

use std::collections::{BTreeMap, BTreeSet};

use minijinja::ErrorKind;
use minijinja::machinery::ast::{Expr, Stmt};
use minijinja::machinery::{Span, Token, parse, tokenize};
use minijinja::syntax::SyntaxConfig;

use super::error::{Callee, Location, TemplateError, TemplateErrorKind};
use super::{BUNDLED_PREFIX, Templates};

impl Templates {
    /// The blocks the page shows (defined or inherited, and not hidden by an
    /// override around them), by name.
    pub fn blocks(&self) -> Result<BTreeSet<String>, TemplateError> {
        Ok(self.analyse()?.shown.into_iter().map(|(name, _)| name).collect())
    }

    /// Checks the custom set for its page.
    pub(super) fn check(&self) -> Result<(), TemplateError> {
        let analysis = self.analyse()?;
        let names: BTreeSet<&str> = analysis.shown.iter().map(|(name, _)| name.as_str()).collect();
        if let Some(block) = self.page.required_blocks().iter().find(|b| !names.contains(*b)) {
            return Err(TemplateError {
                file: self.display(self.entry()),
                location: None,
                kind: TemplateErrorKind::MissingBlock {
                    block: (*block).into(),
                    page: self.page,
                },
            });
        }
        self.check_functions(&analysis)?;
        for (level, name) in analysis.chain.iter().enumerate() {
            if name.starts_with(BUNDLED_PREFIX) {
                continue;
            }
            let hidden = analysis.outlines[name]
                .blocks
                .iter()
                .find(|(block, _)| !analysis.shown.contains(&((*block).clone(), level)));
            if let Some((block, outline)) = hidden {
                return Err(TemplateError {
                    file: self.display(name),
                    location: Some(outline.at),
                    kind: TemplateErrorKind::NeverShown {
                        block: block.clone(),
                        shown: names.iter().map(|n| n.to_string()).collect(),
                    },
                });
            }
        }
        Ok(())
    }

    /// Refuses a function a template calls by a name that is not one of the
    /// environment's (`range`, `dict`, `namespace`, `debug`) and that no
    /// template of the page mentions otherwise (defines as a macro, imports,
    /// assigns, takes as a parameter): nothing could give it a value.
    fn check_functions(&self, analysis: &Analysis) -> Result<(), TemplateError> {
        let globals: BTreeSet<&str> = self.env.globals().map(|(name, _)| name).collect();
        let mentioned = |name: &str| analysis.outlines.values().any(|o| o.mentions.contains(name));
        for (template, outline) in &analysis.outlines {
            let unknown = outline.calls.iter().find(|(callee, called, _)| {
                *callee == Callee::Function && !globals.contains(called.as_str()) && !mentioned(called)
            });
            if let Some((callee, called, at)) = unknown {
                return Err(TemplateError {
                    file: self.display(template),
                    location: Some(*at),
                    kind: TemplateErrorKind::Unknown(*callee, called.clone()),
                });
            }
        }
        Ok(())
    }

    /// Outlines the page's template and every template it names, and follows
    /// its `extends` chain to the blocks it shows.
    fn analyse(&self) -> Result<Analysis, TemplateError> {
        let mut outlines = BTreeMap::new();
        let entry = self.entry();
        if !self.outline(entry, &mut outlines)? {
            return Err(TemplateError {
                file: self.display(entry),
                location: None,
                kind: TemplateErrorKind::MissingPage(self.page),
            });
        }
        let mut chain = vec![entry.to_string()];
        while let Some((parent, at)) = &outlines[chain.last().expect("not empty")].extends {
            if chain.contains(parent) {
                return Err(TemplateError {
                    file: self.display(chain.last().expect("not empty")),
                    location: Some(*at),
                    kind: TemplateErrorKind::Cycle(parent.clone()),
                });
            }
            chain.push(parent.clone());
        }
        let shown = shown(&chain.iter().map(|name| &outlines[name]).collect::<Vec<_>>());
        Ok(Analysis { outlines, chain, shown })
    }

    /// Compiles template `name` and, recursively, every template it names,
    /// adding their outlines to `outlines`; `false` when there is no template
    /// `name`.
    fn outline(&self, name: &str, outlines: &mut BTreeMap<String, Outline>) -> Result<bool, TemplateError> {
        if outlines.contains_key(name) {
            return Ok(true);
        }
        let template = match self.env.get_template(name) {
            Ok(template) => template,
            Err(error) if error.kind() == ErrorKind::TemplateNotFound => return Ok(false),
            Err(error) => return Err(self.error(name, &error)),
        };
        let outline = Outline::of(template.source(), name).map_err(|e| self.error(name, &e))?;
        let refused = [
            (outline.unescaped, TemplateErrorKind::Unescaped),
            (outline.dynamic, TemplateErrorKind::DynamicName),
        ];
        if let Some((at, kind)) = refused.into_iter().find_map(|(at, kind)| Some((at?, kind))) {
            return Err(TemplateError {
                file: self.display(name),
                location: Some(at),
                kind,
            });
        }
        let unknown = outline.calls.iter().find(|(callee, called, _)| match callee {
            Callee::Filter => matches!(self.env.empty_state().apply_filter(called, &[]),
                Err(e) if e.kind() == ErrorKind::UnknownFilter),
            Callee::Test => matches!(self.env.empty_state().perform_test(called, &[]),
                Err(e) if e.kind() == ErrorKind::UnknownTest),
            // Checked with every template's names, in `check`.
            Callee::Function => false,
        });
        if let Some((callee, called, at)) = unknown {
            return Err(TemplateError {
                file: self.display(name),
                location: Some(*at),
                kind: TemplateErrorKind::Unknown(*callee, called.clone()),
            });
        }
        let named: Vec<(String, Location, bool)> = outline
            .extends
            .iter()
            .map(|(parent, at)| (parent.clone(), *at, false))
            .chain(outline.uses.iter().cloned())
            .collect();
        outlines.insert(name.to_string(), outline);
        for (other, at, optional) in named {
            if !self.outline(&other, outlines)? && !optional {
                return Err(TemplateError {
                    file: self.display(name),
                    location: Some(at),
                    kind: TemplateErrorKind::NotFound(self.display(&other)),
                });
            }
        }
        Ok(true)
    }
}

/// What the check needs of one template.
#[derive(Debug, Default)]
struct Outline {
    /// The template it extends, and where.
    extends: Option<(String, Location)>,
    /// The blocks outside any block, in order: where a root template shows them.
    top: Vec<String>,
    /// Every block it defines.
    blocks: BTreeMap<String, BlockOutline>,
    /// Templates it includes or imports by constant name: where, and whether
    /// a missing one is ignored.
    uses: Vec<(String, Location, bool)>,
    /// Where it turns escaping off, if it does.
    unescaped: Option<Location>,
    /// Where it names a template with an expression, if it does.
    dynamic: Option<Location>,
    /// The filters, tests and functions it calls by name, and where.
    calls: Vec<(Callee, String, Location)>,
    /// The names it mentions other than by calling them (what it defines,
    /// imports, assigns or reads).
    mentions: BTreeSet<String>,
}

/// A block as the check sees it.
#[derive(Debug)]
struct BlockOutline {
    at: Location,
    /// The blocks directly inside it.
    nested: Vec<String>,
    /// Whether it shows its parent's body (`super()`).
    calls_super: bool,
}

impl Outline {
    /// The outline of template `name` with text `source`.
    fn of(source: &str, name: &str) -> Result<Self, minijinja::Error> {
        let mut outline = Self::default();
        let tree = parse(source, name, SyntaxConfig::default())?;
        outline.walk(source, std::slice::from_ref(&tree), None);
        // `x|safe`: the filter is removed, and this finds its uses before anything runs.
        let tokens = tokenize(source, false, SyntaxConfig::default()).collect::<Result<Vec<_>, _>>()?;
        for pair in tokens.windows(2) {
            if let [(Token::Pipe, _), (Token::Ident("safe"), span)] = pair {
                outline.unescaped.get_or_insert(Location::of(source, *span));
            }
        }
        outline.names(source, &tokens);
        Ok(outline)
    }

    /// Records the names the tokens call (`x|name`, `{% filter name %}`,
    /// `x is [not] name`, `name(…)`) and mention otherwise.
    fn names(&mut self, source: &str, tokens: &[(Token<'_>, Span)]) {
        for (index, (token, span)) in tokens.iter().enumerate() {
            let Token::Ident(name) = token else { continue };
            let before = |back: usize| index.checked_sub(back).map(|i| &tokens[i].0);
            let callee = match (before(1), before(2)) {
                (Some(Token::Pipe), _) | (Some(Token::Ident("filter")), Some(Token::BlockStart)) => {
                    Some(Callee::Filter)
                }
                (Some(Token::Ident("is")), _) if *name != "not" => Some(Callee::Test),
                (Some(Token::Ident("not")), Some(Token::Ident("is"))) => Some(Callee::Test),
                // `x.name(…)` is a method, `{% name(…) %}` a statement, `macro name(…)` a definition.
                (Some(Token::Dot | Token::BlockStart | Token::Ident("macro")), _) => None,
                _ if KEYWORDS.contains(name) => None,
                _ if matches!(tokens.get(index + 1), Some((Token::ParenOpen, _))) => Some(Callee::Function),
                _ => None,
            };
            match callee {
                Some(callee) => self.calls.push((callee, name.to_string(), Location::of(source, *span))),
                None => {
                    self.mentions.insert(name.to_string());
                }
            }
        }
    }

    /// Records the statements of `body`, inside block `within` if any.
    fn walk(&mut self, source: &str, body: &[Stmt<'_>], within: Option<&str>) {
        for statement in body {
            match statement {
                Stmt::Template(t) => self.walk(source, &t.children, within),
                Stmt::Block(b) => {
                    let span = b.span();
                    let text = &source[span.start_offset as usize..span.end_offset as usize];
                    self.blocks.insert(
                        b.name.to_string(),
                        BlockOutline {
                            at: Location::of(source, span),
                            nested: Vec::new(),
                            calls_super: text.contains("super("),
                        },
                    );
                    match within {
                        Some(outer) => self.blocks.get_mut(outer).expect("walked").nested.push(b.name.into()),
                        None => self.top.push(b.name.into()),
                    }
                    self.walk(source, &b.body, Some(b.name));
                }
                Stmt::Extends(e) => {
                    let at = Location::of(source, e.span());
                    match constant(&e.name) {
                        Some(parent) => self.extends = Some((parent, at)),
                        None => self.dynamic = self.dynamic.or(Some(at)),
                    }
                }
                Stmt::Include(i) => self.name_used(source, &i.name, i.span(), i.ignore_missing),
                Stmt::Import(i) => self.name_used(source, &i.expr, i.span(), false),
                Stmt::FromImport(i) => self.name_used(source, &i.expr, i.span(), false),
                Stmt::AutoEscape(a) => {
                    self.unescaped.get_or_insert(Location::of(source, a.span()));
                }
                Stmt::FilterBlock(f) => {
                    if matches!(&f.filter, Expr::Filter(filter) if filter.name == "safe") {
                        self.unescaped.get_or_insert(Location::of(source, f.span()));
                    }
                    self.walk(source, &f.body, within);
                }
                Stmt::ForLoop(l) => {
                    self.walk(source, &l.body, within);
                    self.walk(source, &l.else_body, within);
                }
                Stmt::IfCond(c) => {
                    self.walk(source, &c.true_body, within);
                    self.walk(source, &c.false_body, within);
                }
                Stmt::WithBlock(w) => self.walk(source, &w.body, within),
                Stmt::SetBlock(s) => self.walk(source, &s.body, within),
                // Blocks are not allowed in macros; nothing else holds statements.
                _ => {}
            }
        }
    }

    fn name_used(&mut self, source: &str, name: &Expr<'_>, span: Span, optional: bool) {
        let at = Location::of(source, span);
        match constant(name) {
            Some(name) => self.uses.push((name, at, optional)),
            None => self.dynamic = self.dynamic.or(Some(at)),
        }
    }
}

/// The words of minijinja's syntax that can stand before a parenthesis
/// without calling anything, and the names a template calls that no template
/// defines (`super()`, `caller()`, `loop(…)` of a recursive loop).
const KEYWORDS: [&str; 11] = [
    "if", "elif", "else", "and", "or", "not", "in", "is", "super", "caller", "loop",
];

/// A template name written as a string constant.
fn constant(name: &Expr<'_>) -> Option<String> {
    name.as_const()?.as_str().map(str::to_string)
}

/// A page's templates as the check sees them.
struct Analysis {
    /// Every template reached by name.
    outlines: BTreeMap<String, Outline>,
    /// The page's template, the template it extends, and so on to the root.
    chain: Vec<String>,
    /// The blocks shown, as (name, level in `chain` of the definition shown).
    shown: BTreeSet<(String, usize)>,
}

/// The blocks a page shows, as (name, level of the definition shown): from the
/// top-level blocks of the root template, each block shown as its most derived
/// definition, with the blocks nested in it, and its parent's definition when
/// it calls `super()`. `chain` runs from the page's template (level 0) to the
/// root.
fn shown(chain: &[&Outline]) -> BTreeSet<(String, usize)> {
    let definition =
        |name: &str, from: usize| (from..chain.len()).find(|&level| chain[level].blocks.contains_key(name));
    let root = chain.last().expect("a chain holds the page's template");
    let mut pending: Vec<(&str, usize)> = root.top.iter().map(|name| (name.as_str(), 0)).collect();
    let mut shown = BTreeSet::new();
    while let Some((name, from)) = pending.pop() {
        let Some(level) = definition(name, from) else {
            continue;
        };
        let (name, block) = chain[level].blocks.get_key_value(name).expect("found above");
        if !shown.insert((name.clone(), level)) {
            continue;
        }
        pending.extend(block.nested.iter().map(|nested| (nested.as_str(), 0)));
        if block.calls_super {
            pending.push((name.as_str(), level + 1));
        }
    }
    shown
}
