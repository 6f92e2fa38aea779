//! MCAP recorder (to be written).
