//! The kernels on lanes that both drivers call, written once over [`Real`]: the model read
//! through [`ModelLanes`] (one flight's, or [`FourModels`] sharing their tables), the 6-DOF
//! derivative, the descent's, and a free-flight step end's figures. The single flight calls
//! them on `f64`, the batch engine on [`F64x4`].

use super::*;

/// What the 6-DOF derivative reads of a flight's model, on lanes: one model per lane, the
/// aerodynamic tables shared by all of them.
pub trait ModelLanes<S: Real> {
    /// The aerodynamic tables (the same for every lane).
    fn aero(&self) -> &AeroTables;
    /// Air density (0 in a vacuum) and speed of sound at a height above the site.
    fn air(&self, h_agl_m: S) -> (S, S);
    /// Wind, inertial, at a height above the site.
    fn wind(&self, h_agl_m: S) -> V3<S>;
    /// Wind, inertial, at a height above the site, and its rate of change with height there
    /// (per metre; zero in a constant wind).
    fn wind_and_shear(&self, h_agl_m: S) -> (V3<S>, V3<S>);
    /// Whether any lane's wind changes with height (a profile): only then do the lifting
    /// surfaces meet winds of their own.
    fn wind_sheared(&self) -> bool;
    /// Gravity's magnitude at a height above the site.
    fn gravity(&self, h_agl_m: S) -> S;
    fn drag_scale(&self) -> S;
    fn nozzle(&self) -> NozzleLanes<S>;
    /// The Earth's rotation in the launch frame, rad/s; `None` when no lane's launch frame
    /// turns (then the Coriolis terms are skipped, not computed as zeros).
    fn earth_rate(&self) -> Option<V3<S>>;
}

impl ModelLanes<f64> for FlightModel {
    #[inline(always)]
    fn aero(&self) -> &AeroTables {
        &self.aero
    }
    #[inline(always)]
    fn air(&self, h: f64) -> (f64, f64) {
        let a = self.air_at(&self.air.at_msl(h + self.env.elevation_m));
        (a.density_kg_m3, a.speed_of_sound_m_s)
    }
    #[inline(always)]
    fn wind(&self, h: f64) -> V3<f64> {
        let [e, n] = self.env.wind.velocity_en(h);
        V3::new(e, n, 0.0)
    }
    #[inline(always)]
    fn wind_and_shear(&self, h: f64) -> (V3<f64>, V3<f64>) {
        let ([e, n], [de, dn]) = self.env.wind.velocity_and_shear_en(h);
        (V3::new(e, n, 0.0), V3::new(de, dn, 0.0))
    }
    #[inline(always)]
    fn wind_sheared(&self) -> bool {
        self.env.wind.varies_with_height()
    }
    #[inline(always)]
    fn gravity(&self, h: f64) -> f64 {
        self.env.gravity.at(h)
    }
    #[inline(always)]
    fn drag_scale(&self) -> f64 {
        self.drag_scale
    }
    #[inline(always)]
    fn nozzle(&self) -> NozzleLanes<f64> {
        self.nozzle.lanes()
    }
    #[inline(always)]
    fn earth_rate(&self) -> Option<V3<f64>> {
        self.earth_rate_n.map(|[x, y, z]| V3::new(x, y, z))
    }
}

/// Four flights' models side by side (their aerodynamic tables must be one and the same:
/// [`FourModels::new`] checks), with what the kernel reads of them packed once.
#[derive(Clone, Copy)]
pub struct FourModels<'a> {
    pub models: [&'a FlightModel; 4],
    nozzle: NozzleLanes<F64x4>,
    drag_scale: F64x4,
    turning: bool,
    /// Whether the four read one air table (else each its own: a site's air swept or
    /// dispersed).
    one_air: bool,
    /// The lanes in a vacuum (no air).
    vacuum: [bool; 4],
    /// The four gravities where none changes with height (the usual case), packed once.
    gravity: Option<F64x4>,
    /// The four winds where none changes with height, packed once (inertial, m/s); `None`
    /// when any lane's does (a profile: then the surfaces meet winds of their own).
    wind: Option<V3<F64x4>>,
}

impl<'a> FourModels<'a> {
    /// `None` unless the four share their aerodynamic tables.
    pub fn new(models: [&'a FlightModel; 4]) -> Option<FourModels<'a>> {
        let same = models
            .iter()
            .all(|m| std::sync::Arc::ptr_eq(&m.aero, &models[0].aero));
        let n = models.map(|m| m.nozzle.lanes());
        same.then(|| FourModels {
            models,
            nozzle: crate::eom::pack_nozzle([&n[0], &n[1], &n[2], &n[3]]),
            drag_scale: F64x4::from_fn(|i| models[i].drag_scale),
            turning: models.iter().any(|m| m.earth_rate_n.is_some()),
            one_air: models
                .iter()
                .all(|m| std::sync::Arc::ptr_eq(&m.air, &models[0].air)),
            vacuum: models.map(|m| m.env.vacuum),
            gravity: constant_lanes(models.map(|m| m.env.gravity.constant_m_s2())).map(F64x4),
            wind: constant_lanes(models.map(|m| m.env.wind.constant_en())).map(|w| {
                let (e, n) = (F64x4(w.map(|w| w[0])), F64x4(w.map(|w| w[1])));
                V3::new(e, n, F64x4::splat(0.0))
            }),
        })
    }
}

/// The four lanes' values if every lane has one.
fn constant_lanes<T: Copy>(v: [Option<T>; 4]) -> Option<[T; 4]> {
    match v {
        [Some(a), Some(b), Some(c), Some(d)] => Some([a, b, c, d]),
        _ => None,
    }
}

impl ModelLanes<F64x4> for FourModels<'_> {
    #[inline(always)]
    fn aero(&self) -> &AeroTables {
        &self.models[0].aero
    }
    #[inline(always)]
    fn air(&self, h: F64x4) -> (F64x4, F64x4) {
        // What `FlightModel::air` does, the four lanes' look-ups side by side in their one table.
        let m = &self.models;
        let z: [f64; 4] = std::array::from_fn(|i| h.0[i] + m[i].env.elevation_m);
        let (rho, sound) = if self.one_air {
            m[0].air.at_msl_four(z)
        } else {
            let a: [_; 4] = std::array::from_fn(|i| m[i].air.at_msl(z[i]));
            (a.map(|a| a.density_kg_m3), a.map(|a| a.speed_of_sound_m_s))
        };
        let rho = F64x4::select(self.vacuum, F64x4::splat(0.0), F64x4(rho));
        (rho, F64x4(sound))
    }
    #[inline(always)]
    fn wind(&self, h: F64x4) -> V3<F64x4> {
        if let Some(w) = self.wind {
            return w;
        }
        // A plain loop, which the compiler inlines (`array::from_fn` left a call per lane).
        let mut w = [V3::<f64>::zero(); 4];
        for (i, w) in w.iter_mut().enumerate() {
            *w = self.models[i].wind(h.0[i]);
        }
        crate::lanes::pack_v3([&w[0], &w[1], &w[2], &w[3]])
    }
    #[inline(always)]
    fn wind_and_shear(&self, h: F64x4) -> (V3<F64x4>, V3<F64x4>) {
        let mut w = [(V3::<f64>::zero(), V3::<f64>::zero()); 4];
        for (i, w) in w.iter_mut().enumerate() {
            *w = self.models[i].wind_and_shear(h.0[i]);
        }
        (
            crate::lanes::pack_v3([&w[0].0, &w[1].0, &w[2].0, &w[3].0]),
            crate::lanes::pack_v3([&w[0].1, &w[1].1, &w[2].1, &w[3].1]),
        )
    }
    #[inline(always)]
    fn wind_sheared(&self) -> bool {
        self.wind.is_none()
    }
    #[inline(always)]
    fn gravity(&self, h: F64x4) -> F64x4 {
        if let Some(g) = self.gravity {
            return g;
        }
        F64x4::from_fn(|i| self.models[i].gravity(h.0[i]))
    }
    #[inline(always)]
    fn drag_scale(&self) -> F64x4 {
        self.drag_scale
    }
    #[inline(always)]
    fn nozzle(&self) -> NozzleLanes<F64x4> {
        self.nozzle
    }
    #[inline(always)]
    fn earth_rate(&self) -> Option<V3<F64x4>> {
        // Packed when asked (turning flights only), not with the rest at every step; a lane
        // without a latitude turns at zero beside the others.
        let rate = |i: usize| self.models[i].earth_rate_n.unwrap_or([0.0; 3]);
        let e = |k: usize| F64x4::from_fn(|i| rate(i)[k]);
        self.turning.then(|| V3::new(e(0), e(1), e(2)))
    }
}

/// The wind (or its shear) times the lanes' gust factor, `gust` (each lane's
/// [`FlightModel::gust`] at its time); `None` when no lane's wind has turbulence: the wind as
/// it is, without the multiplications (a factor of exactly 1 changes no bit either way).
#[inline(always)]
pub(crate) fn gusted<S: Real>(w: V3<S>, gust: Option<S>) -> V3<S> {
    match gust {
        Some(g) => w.scale(g),
        None => w,
    }
}

/// What a descending point feels at height `h_agl_m` above the site, and the speed of sound
/// there, on lanes.
#[inline(always)]
pub fn descent_surroundings<S: Real, L: ModelLanes<S>>(
    lanes: &L,
    h_agl_m: S,
    gust: Option<S>,
) -> (eom::Surroundings<S>, S) {
    let (rho, speed_of_sound) = lanes.air(h_agl_m);
    let at = eom::Surroundings {
        rho,
        g: lanes.gravity(h_agl_m),
        wind_n: gusted(lanes.wind(h_agl_m), gust),
        earth_rate_n: lanes.earth_rate(),
    };
    (at, speed_of_sound)
}

/// What a free-flight step end reads of the mass state: the center of mass and its rates,
/// body axes, on lanes.
#[derive(Debug, Clone, Copy)]
pub struct CenterLanes<S> {
    pub r: V3<S>,
    pub r_rate: V3<S>,
    pub r_accel: V3<S>,
}

impl CenterLanes<f64> {
    #[inline(always)]
    pub fn of(ms: &MassState) -> CenterLanes<f64> {
        CenterLanes {
            r: V3::from_na(&ms.r_cm),
            r_rate: V3::from_na(&ms.r_cm_rate),
            r_accel: V3::from_na(&ms.r_cm_accel),
        }
    }
}

impl CenterLanes<F64x4> {
    /// Set lane `l`.
    #[inline(always)]
    pub fn set_lane(&mut self, l: usize, c: &CenterLanes<f64>) {
        self.r.set_lane(l, &c.r);
        self.r_rate.set_lane(l, &c.r_rate);
        self.r_accel.set_lane(l, &c.r_accel);
    }
}

/// A free-flight step end's figures on lanes ([`end_point_lanes`]).
#[derive(Debug, Clone, Copy)]
pub struct EndLanes<S> {
    /// The center of mass's position and velocity, inertial.
    pub pos: V3<S>,
    pub vel: V3<S>,
    /// The airframe's speed through the air at the center of mass (what the drag reads).
    pub air_speed_m_s: S,
    pub speed_of_sound_m_s: S,
    pub density_kg_m3: S,
    /// Magnitude of the center of mass's inertial acceleration.
    pub accel_cm_m_s2: S,
    /// The air's velocity relative to the airframe at the center of mass, body axes.
    pub air_velocity_b: V3<S>,
}

impl EndLanes<f64> {
    /// The step end's figures, given its mass and the center's body z.
    #[inline(always)]
    pub fn figures(&self, mass_kg: f64, r_cm_z_m: f64) -> EndFigures {
        let aux = FlightAux {
            mass_kg,
            r_cm_z_m,
            air_speed_m_s: self.air_speed_m_s,
            speed_of_sound_m_s: self.speed_of_sound_m_s,
            density_kg_m3: self.density_kg_m3,
            accel_cm_m_s2: self.accel_cm_m_s2,
            air_velocity_b: self.air_velocity_b.to_na(),
        };
        (self.pos.to_na(), self.vel.to_na(), aux)
    }
}

impl EndLanes<F64x4> {
    /// Lane `l`.
    #[inline(always)]
    pub fn lane(&self, l: usize) -> EndLanes<f64> {
        let v = |v: &V3<F64x4>| V3::new(v.x.0[l], v.y.0[l], v.z.0[l]);
        EndLanes {
            pos: v(&self.pos),
            vel: v(&self.vel),
            air_speed_m_s: self.air_speed_m_s.0[l],
            speed_of_sound_m_s: self.speed_of_sound_m_s.0[l],
            density_kg_m3: self.density_kg_m3.0[l],
            accel_cm_m_s2: self.accel_cm_m_s2.0[l],
            air_velocity_b: v(&self.air_velocity_b),
        }
    }
}

/// The figures at the end of a free-flight step whose derivative `dy` is known (the
/// integrator's FSAL stage), given the center of mass there: no aerodynamics. The single
/// flight calls it on one lane ([`FlightModel::end_point`]), the batch on four.
#[inline(always)]
pub fn end_point_lanes<S: Real, L: ModelLanes<S>>(
    lanes: &L,
    gust: Option<S>,
    c: &CenterLanes<S>,
    y: &[S; N6],
    dy: &[S; N6],
) -> EndLanes<S> {
    let r = frames::rotation([y[6], y[7], y[8], y[9]]);
    let omega = V3::new(y[10], y[11], y[12]);
    let pos = V3::new(y[0], y[1], y[2]) + r.mul_v(&c.r);
    // The airframe's velocity at the center of mass, and the center's own (which drifts
    // through the airframe at `r′`): the air meets the first, the trajectory is the second's.
    let v_frame = V3::new(y[3], y[4], y[5]) + r.mul_v(&omega.cross(&c.r));
    let vel = v_frame + r.mul_v(&c.r_rate);
    let (density_kg_m3, speed_of_sound_m_s) = lanes.air(pos.z);
    let v_air_n = v_frame - gusted(lanes.wind(pos.z), gust);
    let a_o_n = V3::new(dy[3], dy[4], dy[5]);
    let w_dot = V3::new(dy[10], dy[11], dy[12]);
    let rel = w_dot.cross(&c.r)
        + omega.cross(&omega.cross(&c.r))
        + omega.cross(&c.r_rate).scale(S::splat(2.0))
        + c.r_accel;
    EndLanes {
        pos,
        vel,
        air_speed_m_s: v_air_n.norm_squared().sqrt(),
        speed_of_sound_m_s,
        density_kg_m3,
        accel_cm_m_s2: (a_o_n + r.mul_v(&rel)).norm_squared().sqrt(),
        air_velocity_b: r.tr_mul_v(&v_air_n),
    }
}

/// The 6-DOF derivative on lanes, given each lane's mass state, thrust and air brakes' drag
/// coefficient (0: closed): the one copy of the free-flight equations (frames, air, wind,
/// loads, gravity, Coriolis, EoM v1).
#[inline(always)]
pub fn derivative_6dof_lanes<S: Real, L: ModelLanes<S>>(
    lanes: &L,
    gust: Option<S>,
    ms: &MassLanes<S>,
    thrust_n: S,
    brake_cd: S,
    y: &[S; N6],
    dy: &mut [S; N6],
) {
    // Two inlined copies, chosen once per call (the `None` one without the Coriolis terms): a
    // test inside the kernel cost the inertial flights 3 % of the batch's instructions (the
    // compiler computed the terms and dropped them).
    match lanes.earth_rate() {
        Some(earth) => derivative_6dof_in(lanes, gust, ms, thrust_n, brake_cd, y, Some(earth), dy),
        None => derivative_6dof_in(lanes, gust, ms, thrust_n, brake_cd, y, None, dy),
    }
}

/// [`derivative_6dof_lanes`] on a turning Earth (`earth_n`, the Earth's rotation in the launch
/// frame) or in an inertial launch frame (`None`).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn derivative_6dof_in<S: Real, L: ModelLanes<S>>(
    lanes: &L,
    gust: Option<S>,
    ms: &MassLanes<S>,
    thrust_n: S,
    brake_cd: S,
    y: &[S; N6],
    earth_n: Option<V3<S>>,
    dy: &mut [S; N6],
) {
    let zero = S::splat(0.0);
    let r = frames::rotation([y[6], y[7], y[8], y[9]]);
    let omega = V3::new(y[10], y[11], y[12]);
    let h = y[2] + r.mul_v(&ms.r).z;
    let (rho, speed_of_sound) = lanes.air(h);
    let v_o_b = r.tr_mul_v(&V3::new(y[3], y[4], y[5]));
    // Each surface meets the wind at its own height, `x` aft of O along the axis's rise:
    // in a profile, the wind at the center of mass plus the shear there times the height
    // between them (the table's own value while both are in one segment of it; the
    // surfaces lie within a body length of the center). A constant wind is `wind_b` itself.
    let rise = r.m[2][2];
    let sheared = lanes.wind_sheared();
    let (wind_b, shear_b) = if sheared {
        let (w, shear) = lanes.wind_and_shear(h);
        (
            r.tr_mul_v(&gusted(w, gust)),
            r.tr_mul_v(&gusted(shear, gust)),
        )
    } else {
        (r.tr_mul_v(&gusted(lanes.wind(h), gust)), V3::zero())
    };
    // The air meets the airframe: at the center of mass, the velocity through the air of the
    // airframe's point there, not of the center itself, which drifts through the airframe at
    // `r′` while the motor burns or a part moves (RocketPy's drag reads its center of dry
    // mass, a point of the airframe; with the drift, every apogee cross-checked against it
    // came out 0.1 to 0.25 m low).
    let v_frame_air_b = v_o_b - wind_b + omega.cross(&ms.r);
    let (mut force, moment) = aero_loads::loads(
        lanes.aero(),
        &v_o_b,
        // In line (a call here, out of the batch's AVX2 code, spilled every vector register
        // around it at each surface).
        #[inline(always)]
        |x_cp: S| {
            if sheared {
                wind_b + shear_b.scale(y[2] - rise * x_cp - h)
            } else {
                wind_b
            }
        },
        &v_frame_air_b,
        &omega,
        rho,
        speed_of_sound,
        thrust_n.gt(zero),
        lanes.drag_scale(),
        brake_cd,
    );
    force.z = force.z + thrust_n;
    let mut g_b = r.tr_mul_v(&V3::new(zero, zero, -lanes.gravity(h)));
    if let Some(earth_n) = earth_n {
        // The Coriolis acceleration of the center of mass, −2 Ω × v_cm (ground-relative),
        // acts on the whole mass there as gravity does, so it joins gravity's field.
        let earth_b = r.tr_mul_v(&earth_n);
        g_b = g_b
            + earth_b
                .cross(&(v_frame_air_b + ms.r_rate + wind_b))
                .scale(S::splat(-2.0));
    }
    let (a_o, w_dot) = eom::accelerations(ms, &force, &moment, &g_b, &omega, &lanes.nozzle());
    eom::rigid_body_derivative_lanes(y, &a_o, &w_dot, &r, dy);
}
