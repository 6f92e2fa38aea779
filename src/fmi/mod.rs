//! FMI 2.0 and 3.0 co-simulation export: all of the crate's unsafe code lives here.
