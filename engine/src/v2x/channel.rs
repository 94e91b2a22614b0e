//! The radio channel of a V2X link (seed 002, eq. 4):
//! RSSI = P_tx − L_path(d) − L_shadow − L_device, and a packet is received when
//! RSSI ≥ the sensitivity. L_shadow is zero-mean Gaussian in dB (log-normal
//! shadowing), drawn once per packet.
//!
//! # Path loss (3GPP TR 36.885 V14.0.0, Annex A.1.4)
//!
//! `d` in metres, `fc` in GHz; a link shorter than 3 m has the loss of a 3 m link
//! (Table A.1.4-1).
//!
//! - **Free space**, which is also the TR's freeway case:
//!   PL_fs = 32.4 + 20 log10 d + 20 log10 fc.
//! - **Urban LOS**, WINNER+ B1: with effective antenna heights h' = h − 1 m and
//!   breakpoint d'_BP = 4 h'_tx h'_rx fc / c (fc in Hz, c = 3·10⁸ m/s),
//!   PL_B1(d) = 22.7 log10 d + 27.0 + 20 log10 fc up to d'_BP and
//!   PL_B1(d) = 40 log10 d + 7.56 − 17.3 log10 h'_tx − 17.3 log10 h'_rx + 2.7 log10 fc
//!   beyond; the link loses max(PL_fs, PL_B1). (WINNER II writes the same lines as
//!   41.0 + 20 log10(fc/5) and 9.45 + 2.7 log10(fc/5); the constants agree to 0.02 dB.)
//! - **Urban NLOS**, WINNER+ B1 Manhattan grid: around one street corner, with legs
//!   d_k then d_l, PL(d_k, d_l) = PL_B1(d_k) + 17.3 − 12.5 n + 10 n log10 d_l + 3 log10 fc,
//!   n = max(2.8 − 0.0024 d_k, 1.84); B1 takes the smaller of PL(d1, d2) and PL(d2, d1).
//!
//! Sources: the TR names the model (B1, 1.5 m antennas, 3 m minimum, shadowing σ of
//! 3 dB LOS and 4 dB NLOS) and gives the freeway line; the B1 constants above are
//! WINNER+ B1 as transcribed in WiLabV2Xsim (`MatFilesInit/initiatePhyParameters.m`,
//! its TR 36.885 urban scenario); the free-space floor follows NIST's ns-3 model of
//! B1 (`cni-urbanmicrocell-propagation-loss-model.cc`), which writes free space as
//! 46.4 + 20 log10 d + 20 log10(fc/5), 0.02 dB from the line above.
//!
//! # Our readings
//!
//! - **NLOS corner (ours).** A straight link blocked by a building gives no street
//!   legs, so we put the corner in the middle: d1 = d2 = d/√2, the legs of a right
//!   angle whose hypotenuse is the link. Both orderings then coincide. The
//!   alternative is B1's hexagonal-layout NLOS line, which needs only d,
//!   PL = (44.9 − 6.55 log10 h) log10 d + 18.38 + 5.83 log10 h + 23 log10 fc with h
//!   the base-station antenna height.
//! - **NLOS is never better than LOS (ours).** Outside its range (legs of a few
//!   metres, antennas barely above 1 m) the corner formula can fall below the LOS
//!   loss of the same distance, so an NLOS link loses max(LOS loss, corner loss), as
//!   TR 38.901 does for its NLOS lines. With seed 002's antennas (1.5 m, 5 m) this
//!   equals max(free space, corner loss).
//! - **Highway NLOS.** The freeway case is LOS only; an NLOS link under the highway
//!   model is treated as LOS, line and shadowing alike.
//! - **Ideal.** No path loss and no shadowing: every packet is received, and
//!   [`transmit`] draws nothing from the random stream.
//!
//! # NR V2X (3GPP TR 37.885 V15, Table 6.2.1-1), `tr37885_urban`
//!
//! The urban grid's V2V lines, `d` in metres, `fc` in GHz, with the same 3 m
//! floor as above (ours: the TR states none for V2V):
//! - **LOS**: PL = 38.77 + 16.7 log10 d + 18.2 log10 fc, shadowing σ 3 dB;
//! - **NLOS** (a building blocks the link): PL = 36.85 + 30 log10 d +
//!   18.9 log10 fc, σ 4 dB (`nlos_shadowing_sigma_db`); above the LOS line at
//!   every distance from 3 m.
//!
//! The TR's third state, NLOSv (a link blocked by vehicles, with an added
//! log-normal blockage loss), is not modelled: only buildings make a link
//! NLOS. The TR's highway line is the freeway line above (`tr36885_highway`).
//! Its 3-D distance is taken in the plane, as every link here is. The constants
//! are checked against ns-3's `ThreeGppV2vUrbanPropagationLossModel`.

use std::f64::consts::SQRT_2;

use rand::{Rng, RngExt};
use rand_distr::StandardNormal;
use sightline_dsl::{Channel, PathLossModel};

use crate::idealisation::Idealisation;

/// Packets do not contend for the channel.
pub(crate) const NO_CONTENTION: Idealisation = Idealisation {
    id: "v2x.no-contention",
    text: "Packets do not contend for the channel (no interference, collisions or congestion): each is received \
           or lost on its own link's power alone, after the fixed `v2x.latency` plus propagation.",
};

/// Shadowing is drawn per packet.
pub(crate) const INDEPENDENT_SHADOWING: Idealisation = Idealisation {
    id: "v2x.independent-shadowing",
    text: "Shadowing is drawn anew for every packet: losses are correlated neither in time nor between nearby \
           receivers.",
};

/// Our reading of B1's corner for a blocked link.
pub(crate) const NLOS_CORNER: Idealisation = Idealisation {
    id: "v2x.nlos-corner",
    text: "A link a building blocks is taken to turn one street corner half-way (WINNER+ B1 Manhattan grid with \
           both legs d/√2).",
};

/// The freeway line everywhere.
pub(crate) const HIGHWAY_LOS: Idealisation = Idealisation {
    id: "v2x.highway-los",
    text: "The freeway model treats every link as line of sight, buildings or not.",
};

/// NR V2X: vehicles never block a link.
pub(crate) const NO_NLOSV: Idealisation = Idealisation {
    id: "v2x.no-nlosv",
    text: "TR 37.885's NLOSv state (a link blocked by vehicles, with its extra blockage loss) is not modelled: only \
           buildings make a link NLOS.",
};

/// Road users never stand in a link's way.
pub(crate) const ROAD_USERS_TRANSPARENT: Idealisation = Idealisation {
    id: "v2x.road-users-transparent",
    text: "Road users never block or weaken a link: only buildings make a link NLOS.",
};

/// No channel at all.
pub(crate) const IDEAL: Idealisation = Idealisation {
    id: "v2x.ideal",
    text: "Every packet arrives (`model: ideal`): no path loss, no shadowing.",
};

/// The idealisations of a path-loss model.
pub(crate) fn path_loss_idealisations(model: PathLossModel) -> &'static [Idealisation] {
    match model {
        PathLossModel::Tr36885Urban => &[INDEPENDENT_SHADOWING, NLOS_CORNER, ROAD_USERS_TRANSPARENT],
        PathLossModel::Tr36885Highway => &[INDEPENDENT_SHADOWING, HIGHWAY_LOS],
        PathLossModel::Tr37885Urban => &[INDEPENDENT_SHADOWING, NO_NLOSV],
        PathLossModel::Ideal => &[IDEAL],
    }
}

/// Shortest distance the path-loss lines are evaluated at; shorter links lose as
/// much as a link of this length (TR 36.885, Table A.1.4-1).
const MIN_DISTANCE_M: f64 = 3.0;

/// Height of the environment (cars, street furniture) that WINNER+ B1 subtracts
/// from antenna heights to get effective heights.
const ENVIRONMENT_HEIGHT_M: f64 = 1.0;

/// Speed of light as WINNER+ rounds it for the breakpoint distance, m/s.
const SPEED_OF_LIGHT: f64 = 3.0e8;

/// One radio link between two antennas.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Link {
    /// Distance between the antennas, metres (non-negative).
    pub distance_m: f64,
    /// Whether the direct path is free of buildings.
    pub los: bool,
    /// Height of the transmitting antenna, metres. The urban model needs it above
    /// 1 m (B1's effective height is h − 1 m).
    pub tx_antenna_m: f64,
    /// Height of the receiving antenna, metres; above 1 m for the urban model.
    pub rx_antenna_m: f64,
}

/// What one packet arrived with.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reception {
    /// Received power including this packet's shadowing, dBm.
    pub rssi_dbm: f64,
    /// Whether the RSSI reached the receiver's sensitivity.
    pub received: bool,
}

/// Path loss of `link` under `channel`'s model, dB (0 for [`PathLossModel::Ideal`]).
pub fn path_loss_db(channel: &Channel, link: &Link) -> f64 {
    debug_assert!(
        link.distance_m >= 0.0,
        "link distance must be non-negative, got {}",
        link.distance_m
    );
    let distance = link.distance_m.max(MIN_DISTANCE_M);
    let carrier = channel.carrier_ghz;
    match channel.model {
        PathLossModel::Ideal => 0.0,
        PathLossModel::Tr36885Highway => free_space_db(distance, carrier),
        PathLossModel::Tr37885Urban if link.los => 38.77 + 16.7 * distance.log10() + 18.2 * carrier.log10(),
        PathLossModel::Tr37885Urban => 36.85 + 30.0 * distance.log10() + 18.9 * carrier.log10(),
        PathLossModel::Tr36885Urban => {
            let heights = effective_heights(link);
            let los = free_space_db(distance, carrier).max(b1_los_db(distance, carrier, heights));
            if link.los {
                los
            } else {
                let leg = distance / SQRT_2;
                los.max(b1_corner_db(leg, leg, carrier, heights))
            }
        }
    }
}

/// Mean received power of `link` (no shadowing): P_tx − L_path − L_device, dBm.
pub fn mean_rssi_dbm(channel: &Channel, link: &Link) -> f64 {
    channel.tx_power_dbm - path_loss_db(channel, link) - channel.device_loss_db
}

/// Sends one packet over `link`: draws its shadowing from `rng` (one standard normal,
/// whatever σ is; nothing under [`PathLossModel::Ideal`]) and applies the
/// sensitivity. The outcome depends only on `rng`'s state.
pub fn transmit(channel: &Channel, link: &Link, rng: &mut impl Rng) -> Reception {
    let mean = mean_rssi_dbm(channel, link);
    if channel.model == PathLossModel::Ideal {
        return Reception {
            rssi_dbm: mean,
            received: true,
        };
    }
    let z: f64 = rng.sample(StandardNormal);
    let rssi_dbm = mean - shadowing_sigma_db(channel, link) * z;
    Reception {
        rssi_dbm,
        received: rssi_dbm >= channel.sensitivity_dbm,
    }
}

/// σ of the shadowing on `link`: the NLOS σ only for a blocked urban link (the
/// freeway case treats every link as LOS).
fn shadowing_sigma_db(channel: &Channel, link: &Link) -> f64 {
    let urban = matches!(channel.model, PathLossModel::Tr36885Urban | PathLossModel::Tr37885Urban);
    if urban && !link.los {
        channel.nlos_shadowing_sigma_db
    } else {
        channel.shadowing_sigma_db
    }
}

/// Effective antenna heights (h'_tx, h'_rx) of WINNER+ B1.
fn effective_heights(link: &Link) -> (f64, f64) {
    let heights = (
        link.tx_antenna_m - ENVIRONMENT_HEIGHT_M,
        link.rx_antenna_m - ENVIRONMENT_HEIGHT_M,
    );
    debug_assert!(
        heights.0 > 0.0 && heights.1 > 0.0,
        "B1 needs antennas above {ENVIRONMENT_HEIGHT_M} m: {link:?}"
    );
    heights
}

/// Free-space loss, the TR's freeway line: 32.4 + 20 log10 d + 20 log10 fc.
fn free_space_db(distance: f64, carrier_ghz: f64) -> f64 {
    32.4 + 20.0 * distance.log10() + 20.0 * carrier_ghz.log10()
}

/// WINNER+ B1 LOS line (at 3 m at least), without the free-space floor.
fn b1_los_db(distance: f64, carrier_ghz: f64, (h_tx, h_rx): (f64, f64)) -> f64 {
    let distance = distance.max(MIN_DISTANCE_M);
    let breakpoint = 4.0 * h_tx * h_rx * carrier_ghz * 1e9 / SPEED_OF_LIGHT;
    if distance <= breakpoint {
        22.7 * distance.log10() + 27.0 + 20.0 * carrier_ghz.log10()
    } else {
        40.0 * distance.log10() + 7.56 - 17.3 * h_tx.log10() - 17.3 * h_rx.log10() + 2.7 * carrier_ghz.log10()
    }
}

/// WINNER+ B1 Manhattan-grid NLOS loss around one corner, `first` metres along the
/// transmitter's street, then `second` along the crossing one.
fn b1_corner_db(first: f64, second: f64, carrier_ghz: f64, heights: (f64, f64)) -> f64 {
    let n = (2.8 - 0.0024 * first).max(1.84);
    b1_los_db(first, carrier_ghz, heights) + 17.3 - 12.5 * n + 10.0 * n * second.log10() + 3.0 * carrier_ghz.log10()
}

#[cfg(test)]
mod tests {
    use approx::assert_abs_diff_eq;
    use proptest::prelude::*;
    use rand::SeedableRng;
    use rand::rngs::ChaCha8Rng;

    /// Probability that a packet on `link` is received:
    /// Φ((mean RSSI − sensitivity) / σ), with σ the LOS or NLOS shadowing σ; a step at
    /// the sensitivity when σ = 0, and 1 under [`PathLossModel::Ideal`].
    fn delivery_probability(channel: &Channel, link: &Link) -> f64 {
        if channel.model == PathLossModel::Ideal {
            return 1.0;
        }
        let margin = mean_rssi_dbm(channel, link) - channel.sensitivity_dbm;
        let sigma = shadowing_sigma_db(channel, link);
        if sigma == 0.0 {
            return if margin >= 0.0 { 1.0 } else { 0.0 };
        }
        normal_cdf(margin / sigma)
    }

    /// Φ(x), the standard normal CDF: erfc(−x/√2) / 2.
    fn normal_cdf(x: f64) -> f64 {
        0.5 * erfc(-x / SQRT_2)
    }

    /// Complementary error function with fractional error below 1.2·10⁻⁷ everywhere:
    /// the Chebyshev fit `erfcc` of Numerical Recipes in C (2nd ed., §6.2).
    fn erfc(x: f64) -> f64 {
        let z = x.abs();
        let t = 1.0 / (1.0 + 0.5 * z);
        let poly = -1.265_512_23
            + t * (1.000_023_68
                + t * (0.374_091_96
                    + t * (0.096_784_18
                        + t * (-0.186_288_06
                            + t * (0.278_868_07
                                + t * (-1.135_203_98
                                    + t * (1.488_515_87 + t * (-0.822_152_23 + t * 0.170_872_77))))))));
        let tail = t * (-z * z + poly).exp();
        if x >= 0.0 { tail } else { 2.0 - tail }
    }

    use super::*;

    // Shared hand arithmetic, fc = 5.9 GHz: log10 5.9 = 0.770852, so
    // 20 log10 fc = 15.417040, 2.7 log10 fc = 2.081300, 3 log10 fc = 2.312556.
    // Free space: 47.817040 + 20 log10 d. B1 before the breakpoint:
    // 42.417040 + 22.7 log10 d. Vehicle antennas (h' = 0.5 m each): d'_BP =
    // 4·0.5·0.5·5.9e9/3e8 = 19.667 m, and beyond it B1 = 40 log10 d + 7.56
    // + 2·17.3·0.301030 + 2.081300 = 40 log10 d + 20.056938.

    /// Path-loss tolerance: the hand arithmetic keeps six decimals.
    const HAND_DB: f64 = 1e-3;

    fn channel(model: PathLossModel) -> Channel {
        Channel {
            model,
            ..Channel::default()
        }
    }

    fn vehicle_link(distance_m: f64, los: bool) -> Link {
        let h = Channel::default().vehicle_antenna_m;
        Link {
            distance_m,
            los,
            tx_antenna_m: h,
            rx_antenna_m: h,
        }
    }

    fn rsu_link(distance_m: f64, los: bool) -> Link {
        let defaults = Channel::default();
        Link {
            distance_m,
            los,
            tx_antenna_m: defaults.vehicle_antenna_m,
            rx_antenna_m: defaults.rsu_antenna_m,
        }
    }

    fn loss(model: PathLossModel, link: Link) -> f64 {
        path_loss_db(&channel(model), &link)
    }

    /// 10 m: B1 = 42.417040 + 22.7 = 65.117040 is below free space 67.817040, so the
    /// floor holds. 50 m: 40·1.698970 + 20.056938 = 88.015738.
    /// 200 m: 40·2.301030 + 20.056938 = 112.098138.
    #[test]
    fn urban_los_by_hand() {
        let urban = PathLossModel::Tr36885Urban;
        assert_abs_diff_eq!(loss(urban, vehicle_link(10.0, true)), 67.817040, epsilon = HAND_DB);
        assert_abs_diff_eq!(loss(urban, vehicle_link(50.0, true)), 88.015738, epsilon = HAND_DB);
        assert_abs_diff_eq!(loss(urban, vehicle_link(200.0, true)), 112.098138, epsilon = HAND_DB);
    }

    /// Legs d/√2. 10 m: leg 7.071068 (log10 0.849485), before the breakpoint, B1 =
    /// 42.417040 + 19.283310 = 61.700350; n = 2.8 − 0.016971 = 2.783029;
    /// 17.3 − 34.787863 + 23.641416 + 2.312556 = 8.466109; total 70.166459.
    /// 50 m: leg 35.355339 (log10 1.548455), B1 = 61.938200 + 20.056938 = 81.995138;
    /// n = 2.715147; 17.3 − 33.939338 + 42.042831 + 2.312556 = 27.716049; total 109.711187.
    /// 200 m: leg 141.421356 (log10 2.150515), B1 = 86.020600 + 20.056938 = 106.077538;
    /// n = 2.460589; 17.3 − 30.757363 + 52.915336 + 2.312556 = 41.770529; total 147.848067.
    #[test]
    fn urban_nlos_by_hand() {
        let urban = PathLossModel::Tr36885Urban;
        assert_abs_diff_eq!(loss(urban, vehicle_link(10.0, false)), 70.166459, epsilon = HAND_DB);
        assert_abs_diff_eq!(loss(urban, vehicle_link(50.0, false)), 109.711187, epsilon = HAND_DB);
        assert_abs_diff_eq!(loss(urban, vehicle_link(200.0, false)), 147.848067, epsilon = HAND_DB);
    }

    /// TR 37.885 at 5.9 GHz (log10 5.9 = 0.770852): LOS 38.77 + 16.7 log10 d +
    /// 14.029506, NLOS 36.85 + 30 log10 d + 14.569103.
    #[test]
    fn nr_urban_by_hand() {
        let nr = PathLossModel::Tr37885Urban;
        for (distance, los, nlos) in [
            (10.0, 69.499507, 81.419103),
            (50.0, 81.172306, 102.388203),
            (200.0, 91.226708, 120.450003),
        ] {
            assert_abs_diff_eq!(loss(nr, vehicle_link(distance, true)), los, epsilon = HAND_DB);
            assert_abs_diff_eq!(loss(nr, vehicle_link(distance, false)), nlos, epsilon = HAND_DB);
        }
    }

    /// 47.817040 + 20 log10 d: 67.817040 at 10 m, + 33.979400 = 81.796440 at 50 m,
    /// + 46.020600 = 93.837640 at 200 m; blocked links lose the same.
    #[test]
    fn highway_by_hand_and_blind_to_nlos() {
        let highway = PathLossModel::Tr36885Highway;
        for (distance, expected) in [(10.0, 67.817040), (50.0, 81.796440), (200.0, 93.837640)] {
            assert_abs_diff_eq!(loss(highway, vehicle_link(distance, true)), expected, epsilon = HAND_DB);
            assert_eq!(
                loss(highway, vehicle_link(distance, false)),
                loss(highway, vehicle_link(distance, true))
            );
        }
        let highway = channel(highway);
        assert_eq!(
            delivery_probability(&highway, &vehicle_link(900.0, false)),
            delivery_probability(&highway, &vehicle_link(900.0, true))
        );
    }

    /// Vehicle to roadside unit (h' = 0.5 m and 4 m): d'_BP = 4·0.5·4·5.9e9/3e8 =
    /// 157.333 m (log10 2.196820). Before: 42.417040 + 49.867814 = 92.284854; beyond:
    /// 87.872800 + 7.56 + 5.207819 − 10.415638 + 2.081300 = 92.306281, a 0.021 dB step
    /// up, both above free space (47.817040 + 43.936400 = 91.753440).
    #[test]
    fn urban_los_is_continuous_at_the_breakpoint() {
        let breakpoint = 4.0 * 0.5 * 4.0 * 5.9e9 / 3.0e8;
        let urban = PathLossModel::Tr36885Urban;
        let before = loss(urban, rsu_link(breakpoint * (1.0 - 1e-12), true));
        let after = loss(urban, rsu_link(breakpoint * (1.0 + 1e-12), true));
        assert_abs_diff_eq!(before, 92.284854, epsilon = HAND_DB);
        assert_abs_diff_eq!(after, 92.306281, epsilon = HAND_DB);
    }

    /// Below 3 m every model loses what it loses at 3 m: free space there is
    /// 47.817040 + 9.542425 = 57.359465, above B1's 42.417040 + 10.830880 = 53.247920.
    #[test]
    fn short_links_lose_the_three_metre_value() {
        for model in [PathLossModel::Tr36885Urban, PathLossModel::Tr36885Highway] {
            for los in [true, false] {
                for distance in [0.0, 1.0, 3.0] {
                    assert_abs_diff_eq!(loss(model, vehicle_link(distance, los)), 57.359465, epsilon = HAND_DB);
                }
            }
        }
    }

    /// Seed 002's defaults, vehicle to roadside unit at 100 m (before the 157 m
    /// breakpoint): B1 = 42.417040 + 45.4 = 87.817040, equal to free space
    /// 47.817040 + 40; RSSI = 23 − 87.817040 − 3 = −67.817040 dBm. Between two
    /// vehicles: 80 + 20.056938 = 100.056938, RSSI −80.056938 dBm.
    #[test]
    fn mean_rssi_at_100_m_with_seed_002_defaults() {
        let defaults = Channel::default();
        assert_abs_diff_eq!(
            mean_rssi_dbm(&defaults, &rsu_link(100.0, true)),
            -67.817040,
            epsilon = HAND_DB
        );
        assert_abs_diff_eq!(
            mean_rssi_dbm(&defaults, &vehicle_link(100.0, true)),
            -80.056938,
            epsilon = HAND_DB
        );
    }

    /// The budget is 23 − 3 + 90 = 110 dB. Vehicle to roadside unit beyond the
    /// breakpoint: 40 log10 d + 7.56 + 5.207819 − 10.415638 + 2.081300 = 110, so
    /// log10 d = (110 − 4.433481) / 40 = 2.639163 and d = 435.675 m.
    #[test]
    fn half_of_the_packets_arrive_where_mean_rssi_meets_the_sensitivity() {
        let defaults = Channel::default();
        let link = rsu_link(435.675, true);
        assert_abs_diff_eq!(
            mean_rssi_dbm(&defaults, &link),
            defaults.sensitivity_dbm,
            epsilon = HAND_DB
        );
        assert_abs_diff_eq!(delivery_probability(&defaults, &link), 0.5, epsilon = 1e-4);
    }

    /// One σ of margin gives Φ(1) = 0.841345; the NLOS σ is 4 dB, the LOS σ 3 dB.
    #[test]
    fn delivery_uses_the_sigma_of_the_link_state() {
        for (los, sigma) in [(true, 3.0), (false, 4.0)] {
            let link = vehicle_link(40.0, los);
            let mut channel = Channel::default();
            channel.sensitivity_dbm = mean_rssi_dbm(&channel, &link) - sigma;
            assert_abs_diff_eq!(delivery_probability(&channel, &link), 0.841_344_746, epsilon = 1e-6);
        }
    }

    #[test]
    fn no_shadowing_makes_delivery_a_step() {
        let channel = Channel {
            shadowing_sigma_db: 0.0,
            nlos_shadowing_sigma_db: 0.0,
            ..Channel::default()
        };
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        for (distance, expected) in [(150.0, true), (200.0, false)] {
            let link = vehicle_link(distance, true);
            assert_eq!(delivery_probability(&channel, &link), if expected { 1.0 } else { 0.0 });
            let reception = transmit(&channel, &link, &mut rng);
            assert_eq!(reception.rssi_dbm, mean_rssi_dbm(&channel, &link));
            assert_eq!(reception.received, expected);
        }
    }

    #[test]
    fn ideal_delivers_everything_and_draws_nothing() {
        let ideal = channel(PathLossModel::Ideal);
        let link = vehicle_link(5_000.0, false);
        assert_eq!(path_loss_db(&ideal, &link), 0.0);
        assert_eq!(delivery_probability(&ideal, &link), 1.0);
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        let reception = transmit(&ideal, &link, &mut rng);
        assert_eq!(
            reception,
            Reception {
                rssi_dbm: 23.0 - 3.0,
                received: true
            }
        );
        assert_eq!(rng, ChaCha8Rng::seed_from_u64(11));
    }

    #[test]
    fn a_packet_depends_only_on_the_rng() {
        let defaults = Channel::default();
        let link = rsu_link(60.0, false);
        let first = transmit(&defaults, &link, &mut ChaCha8Rng::seed_from_u64(3));
        let again = transmit(&defaults, &link, &mut ChaCha8Rng::seed_from_u64(3));
        assert_eq!(first, again);
        assert_eq!(first.received, first.rssi_dbm >= defaults.sensitivity_dbm);
    }

    /// Reference values of Φ (to 10 digits): Φ(1) = 0.8413447461, Φ(−1.96) =
    /// 0.0249978951, Φ(3) = 0.9986501020, Φ(−5) = 2.866515719e−7.
    #[test]
    fn normal_cdf_matches_reference_values() {
        assert_abs_diff_eq!(normal_cdf(0.0), 0.5, epsilon = 1e-7);
        for (x, phi) in [(1.0, 0.841_344_746_1), (-1.96, 0.024_997_895_1), (3.0, 0.998_650_102_0)] {
            assert_abs_diff_eq!(normal_cdf(x), phi, epsilon = 1e-7);
        }
        assert_abs_diff_eq!(normal_cdf(-5.0) / 2.866_515_719e-7, 1.0, epsilon = 1e-6);
    }

    /// Blocked vehicle-to-roadside link at 60 m, where about 58 % arrive: the received
    /// share of 20 000 packets lies within 4 standard errors of the probability.
    #[test]
    fn received_share_matches_delivery_probability() {
        const PACKETS: u32 = 20_000;
        let defaults = Channel::default();
        let link = rsu_link(60.0, false);
        let p = delivery_probability(&defaults, &link);
        assert!(
            (0.2..0.8).contains(&p),
            "pick a distance where the share is informative, p = {p}"
        );
        let mut rng = ChaCha8Rng::seed_from_u64(0x5167_4711_0002);
        let received = (0..PACKETS)
            .filter(|_| transmit(&defaults, &link, &mut rng).received)
            .count();
        let share = received as f64 / f64::from(PACKETS);
        let standard_error = (p * (1.0 - p) / f64::from(PACKETS)).sqrt();
        assert!(
            (share - p).abs() <= 4.0 * standard_error,
            "share {share}, p {p}, se {standard_error}"
        );
    }

    #[test]
    fn proptest_delivery_never_rises_with_distance() {
        let model = prop_oneof![Just(PathLossModel::Tr36885Urban), Just(PathLossModel::Tr36885Highway)];
        let strategy = (
            model,
            any::<bool>(),
            1.1..12.0,
            1.1..12.0,
            0.0..3_000.0_f64,
            0.0..3_000.0_f64,
        );
        let mut runner = crate::pinned::runner(512, 0x5167_4711_0002);
        let result = runner.run(&strategy, |(model, los, h_tx, h_rx, a, b)| {
            let channel = channel(model);
            let link = |distance_m| Link {
                distance_m,
                los,
                tx_antenna_m: h_tx,
                rx_antenna_m: h_rx,
            };
            let (near, far) = (link(a.min(b)), link(a.max(b)));
            prop_assert!(path_loss_db(&channel, &near) <= path_loss_db(&channel, &far) + 1e-9);
            prop_assert!(delivery_probability(&channel, &near) + 1e-12 >= delivery_probability(&channel, &far));
            Ok(())
        });
        if let Err(failure) = result {
            panic!("{failure}");
        }
    }
}
