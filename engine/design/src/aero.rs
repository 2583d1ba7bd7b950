//! Barrowman aerodynamic coefficients (placeholder: filled by the aerodynamics work).
