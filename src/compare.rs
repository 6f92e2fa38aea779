//! Text tables of a run beside the paper's values (what `run` and `report` print).
