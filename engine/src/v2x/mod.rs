//! V2X links (seed 002): how much power a packet arrives with and whether it is
//! received.

mod channel;
mod delivery;

pub use channel::{Link, Reception, path_loss_db, transmit};
pub(crate) use channel::{NO_CONTENTION, path_loss_idealisations};
pub(crate) use delivery::{InFlight, arrival};
