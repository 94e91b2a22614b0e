//! Which files `traces` reads, and reading them: the ones the scenario names,
//! or else the ones its `sumocfg` names (relative to the configuration, as SUMO
//! resolves them), each read once through the caller's [`Loader`] and parsed.

use std::path::{Path as FsPath, PathBuf};

use crate::compile::Loader;
use crate::compile::context::Context;
use crate::compile::reader::{Failed, Named, Reader};
use crate::error::ErrorKind;
use crate::import::sumo::{
    Additional, Config, ConfigFile, Fcd, Network, parse_additional, parse_config, parse_fcd, parse_net,
};
use crate::model::{Import, ImportKind};
use crate::path::Path;
use crate::raw::RawTraces;

/// The files of `traces`, parsed.
pub(super) struct Files {
    /// The trace.
    pub(super) fcd: Fcd,
    /// The network, when there is one.
    pub(super) net: Option<Network>,
    /// The route files (for their vehicle types) and then the additional files,
    /// each with its path as read.
    pub(super) others: Vec<(String, Additional)>,
    /// The path of the trace as read.
    pub(super) fcd_file: String,
    /// Every file as read, for the evidence.
    pub(super) imports: Vec<Import>,
}

/// Reads and parses the files of `raw`; `None` (errors recorded) when one fails.
pub(super) fn read_files(ctx: &mut Context<'_>, raw: &RawTraces, loader: Option<&dyn Loader>) -> Option<Files> {
    let at = Path::root().key("traces");
    let scenario_dir = FsPath::new(ctx.file).parent().unwrap_or(FsPath::new("")).to_path_buf();
    let mut reader = Reader {
        ctx: &mut *ctx,
        loader,
        imports: Vec::new(),
    };
    // The configuration, and the directory its files are relative to.
    let config = match &raw.sumocfg {
        Some(written) => {
            let named = Named::Scenario(at.key("sumocfg"));
            let path = scenario_dir.join(written);
            let config = reader
                .read(&named, &path, ImportKind::SumoConfig, true, parse_config)
                .ok()?;
            let dir = path.parent().unwrap_or(FsPath::new("")).to_path_buf();
            Some((config, path.display().to_string(), dir))
        }
        None => None,
    };
    let from_config = |pick: fn(&Config) -> Vec<&ConfigFile>| -> Vec<(Named, PathBuf)> {
        config
            .iter()
            .flat_map(|(config, file, dir)| {
                pick(config)
                    .into_iter()
                    .map(|f| (Named::Config(file.clone(), f.location), dir.join(&f.path)))
            })
            .collect()
    };
    let from_scenario = |key: &str, written: &[String]| -> Vec<(Named, PathBuf)> {
        written
            .iter()
            .enumerate()
            .map(|(i, w)| {
                let path = at.key(key);
                let path = if key == "routes" { path.index(i) } else { path };
                (Named::Scenario(path), scenario_dir.join(w))
            })
            .collect()
    };
    let choose = |key: &str, written: Option<Vec<String>>, pick: fn(&Config) -> Vec<&ConfigFile>| match written {
        Some(written) => (from_scenario(key, &written), true),
        None => (from_config(pick), false),
    };
    let (fcd, fcd_named) = choose("fcd", raw.fcd.clone().map(|f| vec![f]), |c| c.fcd.iter().collect());
    let (net, net_named) = choose("net", raw.net.clone().map(|f| vec![f]), |c| c.net.iter().collect());
    let (routes, routes_named) = choose("routes", raw.routes.clone(), |c| c.routes.iter().collect());
    let (poly, poly_named) = choose("poly", raw.poly.clone().map(|f| vec![f]), |c| {
        c.additional.iter().collect()
    });
    let Some((named, path)) = fcd.into_iter().next() else {
        let (path, message) = match &raw.sumocfg {
            Some(written) => (
                at.key("sumocfg"),
                format!("`{written}` names no `fcd-output`; name the trace with `traces.fcd`"),
            ),
            None => (at, "`traces` needs `sumocfg` or `fcd`: the trace to replay".to_owned()),
        };
        reader.ctx.error(&path, ErrorKind::Invalid(message));
        return None;
    };
    let fcd_file = path.display().to_string();
    let fcd = reader.read(&named, &path, ImportKind::SumoFcd, fcd_named, parse_fcd);
    let net = net
        .into_iter()
        .next()
        .map(|(named, path)| reader.read(&named, &path, ImportKind::SumoNet, net_named, parse_net))
        .transpose();
    let mut others = Vec::new();
    let mut ok = true;
    for (files, kind, named) in [
        (routes, ImportKind::SumoRoutes, routes_named),
        (poly, ImportKind::SumoPoly, poly_named),
    ] {
        for (at, path) in files {
            match reader.read(&at, &path, kind, named, parse_additional) {
                Ok(additional) => others.push((path.display().to_string(), additional)),
                Err(Failed) => ok = false,
            }
        }
    }
    let (Ok(fcd), Ok(net), true) = (fcd, net, ok) else {
        return None;
    };
    Some(Files {
        fcd,
        net,
        others,
        fcd_file,
        imports: reader.imports,
    })
}
