//! Breakable objects simulated on Rapier.
