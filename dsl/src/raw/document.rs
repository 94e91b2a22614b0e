//! The `document` section: the report as a controlled document.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// The report as a controlled document: its version, who wrote, reviewed and
/// approved it, and the paper it prints on. These keys only label and lay out
/// `report.html` (its document-control table and its page size); they change
/// nothing that is simulated, measured or judged.
#[derive(Debug, Clone, Default, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields, expecting = "a document mapping")]
#[schemars(rename = "Document")]
pub(crate) struct RawDocument {
    /// The document's version as the organisation numbers it (`1.0`, `B`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub version: Option<String>,
    /// Who wrote the scenario and stands behind the report.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub author: Option<String>,
    /// Who reviewed it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reviewer: Option<String>,
    /// Who approved it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub approver: Option<String>,
    /// The paper the report is laid out for when printed: `a4` (the default)
    /// or `letter`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub paper: Option<RawPaper>,
}

/// A paper size.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
#[schemars(rename = "Paper")]
pub(crate) enum RawPaper {
    /// ISO A4, 210 × 297 mm.
    A4,
    /// US Letter, 8.5 × 11 in.
    Letter,
}
