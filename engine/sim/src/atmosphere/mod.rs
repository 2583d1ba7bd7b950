//! The atmosphere (the standard one, a site's, a measured profile): temperature, pressure,
//! density, speed of sound and viscosity of the air as a function of height, for drag and
//! Mach/Reynolds numbers.
//!
//! Model: U.S. Standard Atmosphere 1976 (identical to the ICAO/ISO International Standard
//! Atmosphere below 32 km), the seven lower layers of linear molecular-scale temperature in
//! *geopotential* altitude, from sea level to 86 km geometric. Source: COESA, *U.S. Standard
//! Atmosphere, 1976*, NOAA-S/T 76-1562, U.S. Government Printing Office, 1976 (equations 18,
//! 23, 33a/b, 50, 51 and table 4).
//!
//! Constants (all from that document):
//! - `g0` = 9.80665 m/s², sea-level gravity used to define geopotential altitude;
//! - `R` = R*/M0 = 8314.32 / 28.9644 ≈ 287.05287 J/(kg·K), specific gas constant of air;
//! - `r0` = 6 356 766 m, the Earth radius of the geometric → geopotential conversion
//!   `H = r0·Z / (r0 + Z)`;
//! - sea level: 288.15 K, 101 325 Pa; ratio of specific heats γ = 1.4;
//! - Sutherland's law μ = β T^{3/2} / (T + S), β = 1.458e-6 kg/(m·s·K^½), S = 110.4 K.
//!
//! Layer bases (geopotential m) and lapse rates (K/km): 0 / −6.5, 11 000 / 0, 20 000 / +1.0,
//! 32 000 / +2.8, 47 000 / 0, 51 000 / −2.8, 71 000 / −2.0, top 84 852 (= 86 km geometric).
//! Base temperatures and pressures are computed once, in [`Atmosphere::standard`], from the
//! layer chain (they reproduce the published 22 632.06 Pa, 5 474.889 Pa, … to 7 digits).
//!
//! **A launch site's measured air** ([`AirModel::Site`], OpenRocket's `ExtendedISAModel`
//! with a custom altitude, temperature and pressure): the first layer starts at the site with
//! its temperature and pressure and its temperature runs linearly to the standard 216.65 K at
//! 11 km (geopotential); the layers above are the standard's, their base pressures carried up
//! from the site's. A hot day is less dense all the way up; a site at the standard's own
//! temperature and pressure gives the standard atmosphere. hpr evaluates it, as the standard,
//! in geopotential altitude (OpenRocket in geometric: 0.05 % apart in pressure at 3 km).
//!
//! **A measured temperature profile** ([`AirModel::Profile`], [`AirProfile`]: a sounding's
//! temperatures by height over the site, and the site's pressure): one layer per pair of rows,
//! its temperature linear in geopotential altitude from row to row, its pressure carried up by
//! the same hydrostatic law as the standard's layers; isothermal above the last row. A profile
//! of the standard's own temperatures at its layer bases is the standard atmosphere, and one
//! of a site model's temperatures is that site model (both tested).
//!
//! Conventions and edges:
//! - [`Atmosphere::at`] takes the height **above the launch site (ground)**; the site's
//!   elevation above mean sea level, given once to [`Atmosphere::standard`], is added inside.
//!   [`Atmosphere::at_msl`] takes the geometric altitude above mean sea level directly.
//! - Below −5 km geometric the altitude is **clamped** to −5 km (the air there is returned).
//! - Above 86 km the atmosphere is **extrapolated isothermally** at the 86 km temperature
//!   (186.946 K): pressure and density keep falling exponentially (scale height ≈ 5.5 km),
//!   which stays close to the real upper atmosphere to ~100 km and never goes negative or NaN.
//! - The temperature returned is the molecular-scale temperature `T_M`. It equals the kinetic
//!   temperature below 80 km; between 80 and 86 km the kinetic one is lower by at most 0.04 %
//!   (186.87 vs 186.946 K at 86 km). Pressure and density are exact (ρ = P / (R·T_M)).
//!
//! [`Atmosphere::at`] is pure, allocation-free and branch-light: it is called per derivative
//! evaluation.

use std::sync::Arc;
use thiserror::Error;

/// The natural logarithm of the Reynolds number's scale in air of `density_kg_m3` and
/// `speed_of_sound_m_s`: the Reynolds number at a Mach number there over that in sea-level
/// standard air at the same Mach, `k = (a/a₀)(ν₀/ν)`, with `ν = μ(T)/ρ`, Sutherland's
/// viscosity and `T = a²/(γR)` (the drag estimate's `hpr_design::aero::ReynoldsTables` are
/// read at it). About 0 at sea level (Sutherland's `μ(288.15 K)` is 1.78938e-5 Pa·s against
/// the estimate's 1.7894e-5), −0.47 at 5 km; −∞ in a vacuum.
#[inline]
pub fn reynolds_ln_scale(density_kg_m3: f64, speed_of_sound_m_s: f64) -> f64 {
    use hpr_design::aero::drag_estimate::{
        SEA_LEVEL_KINEMATIC_VISCOSITY_M2_S, SEA_LEVEL_SPEED_OF_SOUND_M_S,
    };
    let a = speed_of_sound_m_s;
    let t = a * a / (GAMMA_AIR * R_AIR_J_KG_K);
    let mu = sutherland_viscosity_pa_s(t);
    (a / SEA_LEVEL_SPEED_OF_SOUND_M_S * SEA_LEVEL_KINEMATIC_VISCOSITY_M2_S * density_kg_m3 / mu)
        .ln()
}

/// Standard gravity used by the geopotential definition, m/s².
pub const G0_M_S2: f64 = 9.80665;
/// Specific gas constant of air, R*/M0 = 8314.32 / 28.9644 ≈ 287.05287 J/(kg·K).
pub const R_AIR_J_KG_K: f64 = 8314.32 / 28.9644;
/// Earth radius of the geometric ↔ geopotential conversion, m.
pub const R0_GEOPOTENTIAL_M: f64 = 6_356_766.0;
/// Ratio of specific heats of air.
pub const GAMMA_AIR: f64 = 1.4;
/// Sea-level standard temperature, K.
pub const T0_K: f64 = 288.15;
/// Sea-level standard pressure, Pa.
pub const P0_PA: f64 = 101_325.0;
/// Sutherland's constant β, kg/(m·s·K^½).
pub const SUTHERLAND_BETA: f64 = 1.458e-6;
/// Sutherland's temperature S, K.
pub const SUTHERLAND_S_K: f64 = 110.4;
/// Lowest geometric altitude above mean sea level of the model (clamped below), m.
pub const MIN_ALTITUDE_MSL_M: f64 = -5_000.0;
/// Top of the tabulated model (isothermal extrapolation above), geometric m.
pub const MAX_ALTITUDE_MSL_M: f64 = 86_000.0;

/// Layer bases in geopotential metres; the last entry is the top of the table (86 km geometric).
pub(crate) const LAYER_BASE_M: [f64; 8] = [
    0.0, 11_000.0, 20_000.0, 32_000.0, 47_000.0, 51_000.0, 71_000.0, 84_852.0,
];
/// Lapse rates dT/dH of the layers starting at `LAYER_BASE_M[i]`, K/m. The last one (above
/// 86 km) is the isothermal extrapolation.
const LAPSE_K_M: [f64; 8] = [-6.5e-3, 0.0, 1.0e-3, 2.8e-3, 0.0, -2.8e-3, -2.0e-3, 0.0];

/// State of the air at one height.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AirState {
    /// Molecular-scale temperature (= kinetic below 80 km), K.
    pub temperature_k: f64,
    /// Static pressure, Pa.
    pub pressure_pa: f64,
    /// Density, kg/m³.
    pub density_kg_m3: f64,
    /// Speed of sound √(γ R T), m/s.
    pub speed_of_sound_m_s: f64,
    /// Dynamic viscosity from Sutherland's law, Pa·s.
    pub dynamic_viscosity_pa_s: f64,
}

/// Which atmosphere a flight flies through.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum AirModel {
    /// The US 1976 standard atmosphere.
    #[default]
    Standard,
    /// The standard atmosphere's layers above 11 km, and below them one layer from a site's
    /// measured air: `temperature_k` and `pressure_pa` at `elevation_m` above mean sea level
    /// (see the module docs).
    Site {
        elevation_m: f64,
        temperature_k: f64,
        pressure_pa: f64,
    },
    /// A measured temperature profile (a sounding) over a site: see [`AirProfile`].
    Profile(Arc<AirProfile>),
}

/// A temperature profile over a launch site, as a radiosonde or a forecast gives it: the
/// temperature at heights above the site, linear in geopotential altitude between rows, and
/// the site's pressure; the pressure above follows the hydrostatic law of each row-to-row
/// layer (the standard atmosphere's own formulas, one layer per pair of rows), so that the
/// density and the speed of sound are consistent with the temperatures at every height.
/// Above the last row the air is isothermal at its temperature; below the site the first
/// layer's lapse continues.
///
/// A row may carry the pressure its source measured there (a weather model's pressure
/// levels, [`AirRow::pressure_pa`]): the layer below it then meets it exactly, its pressure
/// following the same power law of its temperature with the exponent that joins its two
/// rows' pressures. That is the hydrostatic law with the layer's own gas constant, the
/// humid air's (`R T_v / T`) a weather model's heights were integrated with; the rule
/// refuses a layer whose gas constant is more than [`ROW_GAS_CONSTANT_RANGE`] off dry
/// air's (heights, temperatures and pressures that disagree).
#[derive(Debug, Clone, PartialEq)]
pub struct AirProfile {
    /// The site's elevation above mean sea level, m (the rows' heights are above it).
    pub elevation_m: f64,
    /// The site's pressure, Pa.
    pub pressure_pa: f64,
    /// The rows, the first at height 0, heights increasing.
    pub rows: Vec<AirRow>,
}

/// One row of an [`AirProfile`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AirRow {
    /// Height above the site, m.
    pub height_m: f64,
    /// Temperature there, K.
    pub temperature_k: f64,
    /// The pressure measured there, Pa, if the source gives one (never for the first row:
    /// the site's is the profile's `pressure_pa`); `None`: carried up from the row below.
    pub pressure_pa: Option<f64>,
}

/// The range of a layer's gas constant over dry air's between rows with pressures: humid
/// air's is up to 1.5 % above dry air's.
pub const ROW_GAS_CONSTANT_RANGE: (f64, f64) = (0.95, 1.10);

/// Most rows of an [`AirProfile`].
pub const MAX_PROFILE_ROWS: usize = 1000;
/// The highest row of an [`AirProfile`], m above the site (the table's top is 86 km above
/// sea level).
pub const MAX_PROFILE_HEIGHT_M: f64 = 80_000.0;

/// The range of a site's temperature, K (−123 °C to 77 °C: any air a rocket launches into).
pub const SITE_TEMPERATURE_RANGE_K: (f64, f64) = (150.0, 350.0);
/// The range of a site's pressure, Pa.
pub const SITE_PRESSURE_RANGE_PA: (f64, f64) = (10_000.0, 120_000.0);

impl AirModel {
    /// The model whose air at `elevation_m` has the standard atmosphere's temperature or
    /// pressure where `temperature_k` or `pressure_pa` is not given; the standard itself when
    /// neither is.
    pub fn site(
        elevation_m: f64,
        temperature_k: Option<f64>,
        pressure_pa: Option<f64>,
    ) -> Result<AirModel, AtmosphereError> {
        if temperature_k.is_none() && pressure_pa.is_none() {
            return Ok(AirModel::Standard);
        }
        let standard = Atmosphere::standard(0.0)?.at_msl(elevation_m);
        let model = AirModel::Site {
            elevation_m,
            temperature_k: temperature_k.unwrap_or(standard.temperature_k),
            pressure_pa: pressure_pa.unwrap_or(standard.pressure_pa),
        };
        model.check()?;
        Ok(model)
    }

    /// The site's elevation, temperature and pressure this air names, for a launch at
    /// `launch_elevation_m`: a site's own, or the standard's at the launch elevation.
    pub fn site_values(&self, launch_elevation_m: f64) -> (f64, f64, f64) {
        match self {
            &AirModel::Site {
                elevation_m,
                temperature_k,
                pressure_pa,
            } => (elevation_m, temperature_k, pressure_pa),
            AirModel::Profile(p) => (
                p.elevation_m,
                p.rows.first().map_or(f64::NAN, |r| r.temperature_k),
                p.pressure_pa,
            ),
            AirModel::Standard => {
                let a = Atmosphere::standard(0.0)
                    .expect("the standard atmosphere is valid")
                    .at_msl(launch_elevation_m);
                (launch_elevation_m, a.temperature_k, a.pressure_pa)
            }
        }
    }

    /// This air with its site's temperature or pressure changed (a sweep's or a dispersion's):
    /// the air of [`AirModel::site_values`]'s site, the numbers not given kept. A profile
    /// keeps its shape: every row moves by the site temperature's change.
    pub fn with_site_values(
        &self,
        launch_elevation_m: f64,
        temperature_k: Option<f64>,
        pressure_pa: Option<f64>,
    ) -> Result<AirModel, AtmosphereError> {
        if let AirModel::Profile(profile) = self {
            // A warmer or colder day shifts the whole profile by the site's change; a new
            // site pressure carries up through the same temperatures.
            // Measured pressures aloft scale with the site's.
            let t0 = profile.rows.first().map_or(f64::NAN, |r| r.temperature_k);
            let shift = temperature_k.map_or(0.0, |t| t - t0);
            let site_pa = pressure_pa.unwrap_or(profile.pressure_pa);
            let ratio = site_pa / profile.pressure_pa;
            let changed = AirModel::Profile(Arc::new(AirProfile {
                elevation_m: profile.elevation_m,
                pressure_pa: site_pa,
                rows: profile
                    .rows
                    .iter()
                    .map(|r| AirRow {
                        height_m: r.height_m,
                        temperature_k: r.temperature_k + shift,
                        pressure_pa: r
                            .pressure_pa
                            .map(|p| if ratio == 1.0 { p } else { p * ratio }),
                    })
                    .collect(),
            }));
            changed.check()?;
            return Ok(changed);
        }
        let (elevation_m, t, p) = self.site_values(launch_elevation_m);
        AirModel::site(
            elevation_m,
            Some(temperature_k.unwrap_or(t)),
            Some(pressure_pa.unwrap_or(p)),
        )
    }

    /// Check a site's numbers: a finite elevation below the 11 km layer, a temperature and a
    /// pressure within [`SITE_TEMPERATURE_RANGE_K`] and [`SITE_PRESSURE_RANGE_PA`].
    pub fn check(&self) -> Result<(), AtmosphereError> {
        let within = |v: f64, (lo, hi): (f64, f64)| v.is_finite() && (lo..=hi).contains(&v);
        if let AirModel::Profile(p) = self {
            if !(p.elevation_m.is_finite()
                && (MIN_ALTITUDE_MSL_M..=MAX_SITE_ELEVATION_M).contains(&p.elevation_m))
            {
                return Err(AtmosphereError::SiteElevation {
                    value: p.elevation_m,
                });
            }
            if !within(p.pressure_pa, SITE_PRESSURE_RANGE_PA) {
                return Err(AtmosphereError::SitePressure {
                    value: p.pressure_pa,
                });
            }
            if p.rows.is_empty() || p.rows.len() > MAX_PROFILE_ROWS {
                return Err(AtmosphereError::ProfileRows {
                    count: p.rows.len(),
                });
            }
            let mut below = f64::NEG_INFINITY;
            for (row, r) in p.rows.iter().enumerate() {
                let first = row == 0;
                let ok = r.height_m.is_finite()
                    && r.height_m <= MAX_PROFILE_HEIGHT_M
                    && if first {
                        r.height_m == 0.0
                    } else {
                        r.height_m > below
                    };
                if !ok {
                    return Err(AtmosphereError::ProfileHeight {
                        row,
                        value: r.height_m,
                    });
                }
                if !within(r.temperature_k, SITE_TEMPERATURE_RANGE_K) {
                    return Err(AtmosphereError::ProfileTemperature {
                        row,
                        value: r.temperature_k,
                    });
                }
                below = r.height_m;
            }
            // Measured pressures: after the site, falling, each layer's gas constant dry
            // air's within the range.
            let layers = profile_layers(p);
            for (row, r) in p.rows.iter().enumerate() {
                let Some(value) = r.pressure_pa else {
                    continue;
                };
                let under = layers[row.saturating_sub(1)];
                let ok = row > 0
                    && value.is_finite()
                    && value > 0.0
                    && value < under.p_base_pa
                    && (ROW_GAS_CONSTANT_RANGE.0..=ROW_GAS_CONSTANT_RANGE.1)
                        .contains(&under.gas_constant_ratio());
                if !ok {
                    return Err(AtmosphereError::ProfilePressure {
                        row,
                        value,
                        below_pa: under.p_base_pa,
                        ratio: under.gas_constant_ratio(),
                    });
                }
            }
            return Ok(());
        }
        if let AirModel::Site {
            elevation_m,
            temperature_k,
            pressure_pa,
        } = *self
        {
            if !(elevation_m.is_finite()
                && (MIN_ALTITUDE_MSL_M..=MAX_SITE_ELEVATION_M).contains(&elevation_m))
            {
                return Err(AtmosphereError::SiteElevation { value: elevation_m });
            }
            if !within(temperature_k, SITE_TEMPERATURE_RANGE_K) {
                return Err(AtmosphereError::SiteTemperature {
                    value: temperature_k,
                });
            }
            if !within(pressure_pa, SITE_PRESSURE_RANGE_PA) {
                return Err(AtmosphereError::SitePressure { value: pressure_pa });
            }
        }
        Ok(())
    }
}

/// The highest site whose air can be given: 10 km, below the 11 km layer that the site's
/// first layer runs to.
pub const MAX_SITE_ELEVATION_M: f64 = 10_000.0;

/// Invalid atmosphere settings.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum AtmosphereError {
    /// The launch-site elevation is not a finite number within the model's range.
    #[error(
        "atmosphere: `launch_elevation_m` = {value} m: must be finite and within \
         [{MIN_ALTITUDE_MSL_M}, {MAX_ALTITUDE_MSL_M}] m above mean sea level"
    )]
    LaunchElevation {
        /// The rejected value, m.
        value: f64,
    },
    /// A site's air given at an elevation outside −5 km to 10 km.
    #[error(
        "atmosphere: the site's air is given at {value} m: the elevation must be finite and \
         within [{MIN_ALTITUDE_MSL_M}, {MAX_SITE_ELEVATION_M}] m above mean sea level (below \
         the 11 km layer)"
    )]
    SiteElevation { value: f64 },
    /// A site temperature outside [`SITE_TEMPERATURE_RANGE_K`].
    #[error(
        "atmosphere: field \"temperature_k\" = {value}: the site's temperature must be \
         finite and within [{}, {}] K", SITE_TEMPERATURE_RANGE_K.0, SITE_TEMPERATURE_RANGE_K.1
    )]
    SiteTemperature { value: f64 },
    /// A site pressure outside [`SITE_PRESSURE_RANGE_PA`].
    #[error(
        "atmosphere: field \"pressure_pa\" = {value}: the site's pressure must be finite \
         and within [{}, {}] Pa", SITE_PRESSURE_RANGE_PA.0, SITE_PRESSURE_RANGE_PA.1
    )]
    SitePressure { value: f64 },
    /// An air profile with no rows, or too many.
    #[error(
        "atmosphere: field \"air_profile\": {count} rows: a profile has 1 to \
         {MAX_PROFILE_ROWS} rows"
    )]
    ProfileRows { count: usize },
    /// A profile row's height: the first must be 0 (the site), each next one higher.
    #[error(
        "atmosphere: field \"air_profile[{row}].height_m\" = {value}: the first row is at the \
         site (height 0) and each row is higher than the one before, up to \
         {MAX_PROFILE_HEIGHT_M} m above the site"
    )]
    ProfileHeight { row: usize, value: f64 },
    /// A profile row's measured pressure: not below the row beneath's, or one that asks of
    /// the layer beneath a gas constant outside [`ROW_GAS_CONSTANT_RANGE`] of dry air's.
    #[error(
        "atmosphere: field \"air_profile[{row}].pressure_pa\" = {value}: a row's pressure must \
         be finite and below the row beneath's ({below_pa} Pa), and agree with the heights and \
         temperatures between them (it asks of the air a gas constant {ratio:.4} times dry \
         air's; humid air's is at most 1.02 times)"
    )]
    ProfilePressure {
        row: usize,
        value: f64,
        below_pa: f64,
        ratio: f64,
    },
    /// A profile row's temperature outside [`SITE_TEMPERATURE_RANGE_K`].
    #[error(
        "atmosphere: field \"air_profile[{row}].temperature_k\" = {value}: must be finite and \
         within [{}, {}] K", SITE_TEMPERATURE_RANGE_K.0, SITE_TEMPERATURE_RANGE_K.1
    )]
    ProfileTemperature { row: usize, value: f64 },
}

/// One layer of the model, precomputed.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Layer {
    base_m: f64,
    lapse_k_m: f64,
    t_base_k: f64,
    p_base_pa: f64,
    /// `g0 / (R L)` for a gradient layer, `g0 / (R T_b)` for an isothermal one.
    exponent: f64,
}

/// The standard atmosphere (or a site's air, or a profile) seen from one launch site.
#[derive(Debug, Clone, PartialEq)]
pub struct Atmosphere {
    launch_elevation_m: f64,
    /// Layers by base, lowest first (the first also serves below its base).
    layers: Vec<Layer>,
}

impl Atmosphere {
    /// The US 1976 standard atmosphere over a site `launch_elevation_m` above mean sea level.
    pub fn standard(launch_elevation_m: f64) -> Result<Self, AtmosphereError> {
        Atmosphere::new(launch_elevation_m, &AirModel::Standard)
    }

    /// The atmosphere `model` over a site `launch_elevation_m` above mean sea level.
    pub fn new(launch_elevation_m: f64, model: &AirModel) -> Result<Self, AtmosphereError> {
        if !launch_elevation_m.is_finite()
            || !(MIN_ALTITUDE_MSL_M..=MAX_ALTITUDE_MSL_M).contains(&launch_elevation_m)
        {
            return Err(AtmosphereError::LaunchElevation {
                value: launch_elevation_m,
            });
        }
        model.check()?;
        let layers = match *model {
            AirModel::Profile(ref profile) => profile_layers(profile),
            // The first layer: the standard's from sea level, or the site's to 11 km; the
            // standard's above.
            AirModel::Standard => standard_layers(LAYER_BASE_M[0], T0_K, P0_PA, LAPSE_K_M[0]),
            AirModel::Site {
                elevation_m,
                temperature_k,
                pressure_pa,
            } => {
                let base = geopotential_altitude_m(elevation_m);
                let t11 = T0_K + LAPSE_K_M[0] * LAYER_BASE_M[1];
                let lapse = (t11 - temperature_k) / (LAYER_BASE_M[1] - base);
                standard_layers(base, temperature_k, pressure_pa, lapse)
            }
        };
        Ok(Self {
            launch_elevation_m,
            layers,
        })
    }

    /// Elevation of the launch site above mean sea level, m.
    pub fn launch_elevation_m(&self) -> f64 {
        self.launch_elevation_m
    }

    /// The air at `altitude_above_ground_m` metres above the launch site (the site elevation
    /// is added here). See the module docs for the behaviour outside −5 km … 86 km MSL.
    #[inline]
    pub fn at(&self, altitude_above_ground_m: f64) -> AirState {
        self.at_msl(self.launch_elevation_m + altitude_above_ground_m)
    }

    /// The air at geometric altitude `altitude_msl_m` above mean sea level.
    #[inline]
    pub fn at_msl(&self, altitude_msl_m: f64) -> AirState {
        let z = altitude_msl_m.max(MIN_ALTITUDE_MSL_M);
        let h = geopotential_altitude_m(z);
        // The last layer whose base is below h (the first below its own base).
        let mut i = self.layers.len() - 1;
        while i > 0 && h < self.layers[i].base_m {
            i -= 1;
        }
        let layer = &self.layers[i];
        let (t, p) = layer.temperature_pressure(h - layer.base_m);
        air_state(t, p)
    }
}

/// The standard's eight layers above a first one from `base0` (geopotential m) at `t0`, `p0`
/// with lapse `lapse0`, each layer's base temperature and pressure carried up from the one
/// below.
fn standard_layers(base0: f64, t0: f64, p0: f64, lapse0: f64) -> Vec<Layer> {
    let mut layers = Vec::with_capacity(LAYER_BASE_M.len());
    let (mut t_b, mut p_b) = (t0, p0);
    for i in 0..LAYER_BASE_M.len() {
        let (base, lapse) = match i {
            0 => (base0, lapse0),
            _ => (LAYER_BASE_M[i], LAPSE_K_M[i]),
        };
        let layer = Layer::new(base, lapse, t_b, p_b);
        if let Some(&top) = LAYER_BASE_M.get(i + 1) {
            (t_b, p_b) = layer.temperature_pressure(top - base);
        }
        layers.push(layer);
    }
    layers
}

/// A profile's layers: one per pair of rows, its temperature linear in geopotential altitude
/// from one row's to the next's, its pressure carried up from the site's by each layer's
/// hydrostatic law; then an isothermal layer from the last row up.
fn profile_layers(profile: &AirProfile) -> Vec<Layer> {
    let bases: Vec<f64> = profile
        .rows
        .iter()
        .map(|r| geopotential_altitude_m(profile.elevation_m + r.height_m))
        .collect();
    let mut layers = Vec::with_capacity(profile.rows.len());
    let (mut t_b, mut p_b) = (profile.rows[0].temperature_k, profile.pressure_pa);
    for (i, &base) in bases.iter().enumerate() {
        let lapse = match profile.rows.get(i + 1) {
            Some(next) => (next.temperature_k - t_b) / (bases[i + 1] - base),
            None => 0.0,
        };
        let mut layer = Layer::new(base, lapse, t_b, p_b);
        if let Some(&top) = bases.get(i + 1) {
            let next = &profile.rows[i + 1];
            match next.pressure_pa {
                // A measured pressure: the layer meets it.
                Some(p_top) => {
                    layer.exponent = if layer.lapse_k_m == 0.0 {
                        (p_b / p_top).ln() / (top - base)
                    } else {
                        (p_top / p_b).ln() / (t_b / (t_b + layer.lapse_k_m * (top - base))).ln()
                    };
                    p_b = p_top;
                }
                // The next row's temperature as given (not the lapse's rounding of it), the
                // pressure carried up.
                None => p_b = layer.temperature_pressure(top - base).1,
            }
            t_b = next.temperature_k;
        }
        layers.push(layer);
    }
    layers
}

impl Layer {
    /// The layer from `base_m` (geopotential m) with lapse `lapse_k_m` from `t_base_k`,
    /// `p_base_pa`. A lapse under 1e-9 K/m is isothermal (its power would lose its digits).
    fn new(base_m: f64, lapse_k_m: f64, t_base_k: f64, p_base_pa: f64) -> Layer {
        let lapse_k_m = if lapse_k_m.abs() < 1e-9 {
            0.0
        } else {
            lapse_k_m
        };
        Layer {
            base_m,
            lapse_k_m,
            t_base_k,
            p_base_pa,
            exponent: if lapse_k_m == 0.0 {
                G0_M_S2 / (R_AIR_J_KG_K * t_base_k)
            } else {
                G0_M_S2 / (R_AIR_J_KG_K * lapse_k_m)
            },
        }
    }

    /// The layer's gas constant over dry air's: 1 for a layer carried up hydrostatically,
    /// the ratio its exponent implies for one that meets a measured pressure.
    fn gas_constant_ratio(&self) -> f64 {
        let hydrostatic = if self.lapse_k_m == 0.0 {
            G0_M_S2 / (R_AIR_J_KG_K * self.t_base_k)
        } else {
            G0_M_S2 / (R_AIR_J_KG_K * self.lapse_k_m)
        };
        hydrostatic / self.exponent
    }

    /// Temperature and pressure `dh` geopotential metres above this layer's base.
    #[inline]
    fn temperature_pressure(&self, dh: f64) -> (f64, f64) {
        if self.lapse_k_m == 0.0 {
            (self.t_base_k, self.p_base_pa * (-self.exponent * dh).exp())
        } else {
            let t = self.t_base_k + self.lapse_k_m * dh;
            (t, self.p_base_pa * (self.t_base_k / t).powf(self.exponent))
        }
    }
}

/// Geopotential altitude (m') of geometric altitude `z_m` above mean sea level:
/// `H = r0 Z / (r0 + Z)`.
#[inline]
pub fn geopotential_altitude_m(z_m: f64) -> f64 {
    R0_GEOPOTENTIAL_M * z_m / (R0_GEOPOTENTIAL_M + z_m)
}

/// Geometric altitude of geopotential altitude `h_m`: `Z = r0 H / (r0 − H)`.
#[inline]
pub fn geometric_altitude_m(h_m: f64) -> f64 {
    R0_GEOPOTENTIAL_M * h_m / (R0_GEOPOTENTIAL_M - h_m)
}

/// Derived quantities of air at temperature `t` K and pressure `p` Pa.
#[inline]
fn air_state(t: f64, p: f64) -> AirState {
    AirState {
        temperature_k: t,
        pressure_pa: p,
        density_kg_m3: p / (R_AIR_J_KG_K * t),
        speed_of_sound_m_s: (GAMMA_AIR * R_AIR_J_KG_K * t).sqrt(),
        dynamic_viscosity_pa_s: sutherland_viscosity_pa_s(t),
    }
}

/// Dynamic viscosity of air at `t` K by Sutherland's law, Pa·s.
#[inline]
fn sutherland_viscosity_pa_s(t: f64) -> f64 {
    SUTHERLAND_BETA * t * t.sqrt() / (t + SUTHERLAND_S_K)
}

mod table;
pub use table::{Air, AirTable, AIR_TABLE_STEP_M};

#[cfg(test)]
mod profile_tests;
#[cfg(test)]
mod site_tests;
#[cfg(test)]
mod tests;
