//! A joint world (`perception` and `semantic` together): what would be
//! ambiguous with one scene for both models, refused where it is written.
//!
//! - One ego: the ego the grid is fused for is the ego the roadside units
//!   assist (`perception.ego` = `semantic.ego`).
//! - One run per seed: the grid's jobs and the pipeline share one scene, so
//!   `semantic.runs` cannot pool more (checks over `seeds` and `seed` sweeps
//!   serve instead).
//! - `v2x.penetration` would mean both how many agents cooperate in the grid
//!   and which generated or imported road users send their own state: the
//!   cooperating agents are named by `perception.cooperating`, and generated
//!   and imported road users are not connected.

use crate::compile::context::Context;
use crate::error::ErrorKind;
use crate::model::{Agent, Perception, Semantic};
use crate::path::Path;
use crate::raw::RawScenario;

/// Checks what a joint world may not say, given its compiled `perception` and
/// `semantic` (each `None` where it failed with its own errors); whether all
/// holds.
pub(super) fn joint(
    ctx: &mut Context<'_>,
    raw: &RawScenario,
    agents: &[Agent],
    (perception, semantic): (Option<&Perception>, Option<&Semantic>),
) -> bool {
    let root = Path::root();
    let mut ok = true;
    if raw.v2x.as_ref().is_some_and(|v2x| v2x.penetration.is_some()) {
        ctx.error(
            &root.key("v2x").key("penetration"),
            ErrorKind::Invalid(
                "in a joint world `penetration` would mean both how many agents cooperate in the grid and which \
                 generated and imported road users send the ego their own state: name the cooperating agents \
                 with `perception.cooperating`; generated and imported road users are not connected"
                    .into(),
            ),
        );
        ok = false;
    }
    if let Some(semantic) = semantic.filter(|s| s.runs > 1) {
        ctx.error(
            &root.key("semantic").key("runs"),
            ErrorKind::Invalid(format!(
                "a joint world runs its grid and its pipeline on one scene, once per seed, and cannot pool {} runs: \
                 judge over seeds (`seeds` on a check) or sweep `seed` instead",
                semantic.runs
            )),
        );
        ok = false;
    }
    if let (Some(perception), Some(semantic)) = (perception, semantic)
        && perception.ego != semantic.ego
    {
        ctx.error(
            &root.key("semantic").key("ego"),
            ErrorKind::Invalid(format!(
                "a joint world has one ego: the roadside units assist `{}` and the grid is fused for `{}` \
                 (`perception.ego`)",
                agents[semantic.ego].id, agents[perception.ego].id
            )),
        );
        ok = false;
    }
    ok
}
