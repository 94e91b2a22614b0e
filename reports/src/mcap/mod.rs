//! `run.mcap`: a run recorded in Foxglove's formats, written as the engine runs
//! and read back by `sightline replay`.

pub use read::{ReadError, RecordedRun, Recording, read};
pub use wire::{
    AgentSpeed, ApproachRecord, ArrivalRecord, AuditRecord, CellSignals, ConflictRecord, ImportRecord, ItemRecord,
    MessageRecord, MetricValue, ObjectRecord, ObjectValue, OutcomeRecord, PacketRecord, PointVerdictRecord,
    RECORDING_FORMAT, Real, ReplicateRecord, RequirementSignal, RequirementSignals, ScenarioRecord, SemanticSignals,
    SeriesRecord, SeriesRun, SeriesSample, SignalsRecord, SpeedsRecord, VerdictRecord,
};
pub use write::{Recorder, Source, WriteError};

mod counts;
mod flat;
mod foxglove;
mod lengths;
mod read;
pub mod topic;
mod wire;
mod write;
