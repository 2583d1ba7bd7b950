"""What the cross-checks correct in RocketPy 1.13 before comparing it with hpr-mc.

Two things hpr-mc does not share, each corrected on RocketPy's side so that RocketPy itself
measures its worth (the scripts fly every case as RocketPy is, too):

* ``true_speed_of_sound(env)``: RocketPy's speed of sound is the chord of sqrt(1.4 R T)
  between its ISA table's layer boundaries (``calculate_speed_of_sound_profile`` applies the
  square root to a ``Function`` sampled only there and interpolates linearly), 0.10 % low
  at 1400 m, 0.16 % at 2500 m. This puts the true curve in its place.
* ``true_standard_air(env)``: the same for the air itself. RocketPy's standard temperature is
  interpolated linearly in geometric height between its layers' bases (0.014 K warm at
  1400 m) and its pressure is a spline through 100 samples 808 m apart (5 Pa low at 1400 m),
  so its density is 6e-5 to 1.2e-4 below the U.S. Standard Atmosphere 1976 between 1.4 and
  5.4 km. This gives ``env`` the standard's temperature, pressure, density and speed of sound,
  in geopotential height, as hpr-mc has them (``hpr_sim::atmosphere``), and the barometric
  height a parachute's trigger reads as that pressure's exact inverse.
* ``correct(rocket)``: the lever arm's sign (RocketPy issue #1186), below.

The lever arm.

``Flight.u_dot_generalized`` writes the equations of motion v1 about the center of dry mass
(CDM) with ``r_CM`` the center of mass seen from the CDM and ``r_NOZ`` the nozzle seen from
it, but reads them from ``Rocket.com_to_cdm_function`` and ``Rocket.nozzle_to_cdm``, which run
the other way (CM to CDM, nozzle to CDM). ``correct(rocket)`` negates both attributes, so
that every term that uses them as the v1 derivation does gets the right sign: the mass-flow
terms, the inertia about the center of mass, the weight's moment and the angular solve
``w_dot = I_CM^-1 (T21 + T20 x r_CM)``.

One term was written for the attribute as it is: the translational equation
``v_dot = K (T20 / m - r_CM x w_dot)``. For the acceleration of the CDM it must be
``T20 / m - w_dot x r_CM = T20 / m + r_CM x w_dot`` with ``r_CM`` from the CDM (then
``m (v_dot + w_dot x r_CM + w x (w x r_CM) + ...)`` is ``m a_CM``, as RocketPy issue #1186
shows);
RocketPy's ``- r_CM x w_dot`` is that only with ``r_CM`` from the CM. So after negating the
attribute this term has the wrong sign, and ``u_dot`` below adds ``2 K (r_CM x w_dot)`` back.
Measured at a state of the canted, boattailed rocket 0.3 s after liftoff in wind: without it
the CDM's acceleration is 1.4 m/s^2 off across the axis; with it RocketPy's derivative matches
hpr-mc's to 1e-3 m/s^2 and 1e-4 of w_dot (the rest is the speed of sound's Mach in the drag).

The patch wraps ``Flight.u_dot_generalized`` for rockets marked by ``correct`` only, and must
be installed (by importing this module) before the ``Flight`` is built, since RocketPy flies
in ``Flight.__init__``. It changes the integrated state, not the accelerations RocketPy keeps
for its post-processed outputs (``Flight.ax`` and the like), which these scripts do not use.
"""

import math

from rocketpy import Flight, Function
from rocketpy.mathutils.vector_matrix import Matrix, Vector

_MARK = "_hpr_mc_lever_arm_corrected"
_UNPATCHED = Flight.u_dot_generalized


def true_speed_of_sound(env):
    """Give ``env`` the speed of sound sqrt(1.4 R T(h)) at every height, as hpr-mc has it."""
    gas = env.air_gas_constant
    temperature = env.temperature
    env.speed_of_sound = Function(
        lambda h: (1.4 * gas * temperature.get_value_opt(h)) ** 0.5,
        "Height Above Sea Level (m)", "Speed of Sound (m/s)")
    return env


# The U.S. Standard Atmosphere 1976 (COESA), its constants as hpr_sim::atmosphere's.
_G0 = 9.80665
_R_AIR = 8314.32 / 28.9644
_R0 = 6356766.0
# (base geopotential height m, lapse rate K/m) of the four lowest layers (to 47 km).
_LAYERS = [(0.0, -6.5e-3), (11000.0, 0.0), (20000.0, 1.0e-3), (32000.0, 2.8e-3)]


def _layer_bases():
    """Each layer's (base height, lapse, base temperature, base pressure)."""
    bases, t, p = [], 288.15, 101325.0
    for i, (h0, lapse) in enumerate(_LAYERS):
        bases.append((h0, lapse, t, p))
        if i + 1 < len(_LAYERS):
            t, p = _temperature_pressure(bases[-1], _LAYERS[i + 1][0])
    return bases


def _temperature_pressure(base, h):
    h0, lapse, t0, p0 = base
    if lapse == 0.0:
        return t0, p0 * math.exp(-_G0 * (h - h0) / (_R_AIR * t0))
    t = t0 + lapse * (h - h0)
    return t, p0 * (t0 / t) ** (_G0 / (_R_AIR * lapse))


_BASES = _layer_bases()


def standard_air(z_m):
    """Temperature (K) and pressure (Pa) of the 1976 standard at geometric height z_m above
    sea level (below 47 km geopotential)."""
    h = _R0 * z_m / (_R0 + z_m)
    assert h < 47000.0, "above the layers this correction carries"
    base = [b for b in _BASES if b[0] <= h][-1] if h >= 0.0 else _BASES[0]
    return _temperature_pressure(base, h)


def true_standard_air(env):
    """Give ``env`` the 1976 standard's air at every height, as hpr-mc has it."""
    return set_air(env, standard_air, standard_height)


def set_air(env, air, height_of):
    """Give ``env`` the air ``air(z)`` = (temperature K, pressure Pa) at geometric height z
    above sea level, its density and speed of sound from them, and ``height_of(p)``, the
    inverse of its pressure, as its barometric height."""
    height = "Height Above Sea Level (m)"
    env.temperature = Function(lambda z: air(z)[0], height, "Temperature (K)")
    env.pressure = Function(lambda z: air(z)[1], height, "Pressure (Pa)")

    def density(z):
        t, p = air(z)
        return p / (_R_AIR * t)

    env.density = Function(density, height, "Air Density (kg/m³)")
    env.speed_of_sound = Function(
        lambda z: (1.4 * _R_AIR * air(z)[0]) ** 0.5, height, "Speed of Sound (m/s)")
    # A parachute's height trigger reads the height of its (noise-free) pressure: the
    # pressure's own inverse, not RocketPy's, which inverts its former pressure through 100
    # samples and puts the main's trigger a few centimetres off.
    env.barometric_height = Function(height_of, "Pressure (Pa)", height)
    return env


def standard_height(p_pa):
    """Geometric height above sea level (m) of the 1976 standard's pressure p_pa (the inverse
    of ``standard_air``'s pressure, below 47 km geopotential)."""
    h0, lapse, t0, p0 = [b for b in _BASES if b[3] >= p_pa][-1] if p_pa <= _BASES[0][3] \
        else _BASES[0]
    if lapse == 0.0:
        h = h0 - _R_AIR * t0 / _G0 * math.log(p_pa / p0)
    else:
        h = h0 + (t0 * (p_pa / p0) ** (-_R_AIR * lapse / _G0) - t0) / lapse
    return _R0 * h / (_R0 - h)


def correct(rocket):
    """Give ``rocket`` the lever arm's sign the equations of motion v1 define."""
    rocket.com_to_cdm_function = -1 * rocket.com_to_cdm_function
    rocket.nozzle_to_cdm = -rocket.nozzle_to_cdm
    setattr(rocket, _MARK, True)
    return rocket


def _u_dot(self, t, u, post_processing=False):
    du = _UNPATCHED(self, t, u, post_processing=post_processing)
    if not getattr(self.rocket, _MARK, False):
        return du
    r_cm = Vector([0, 0, self.rocket.com_to_cdm_function.get_value_opt(t)])
    w_dot = Vector(du[10:13])
    fix = Matrix.transformation(u[6:10]) @ (2 * (r_cm ^ w_dot))
    du = list(du)
    du[3] += fix.x
    du[4] += fix.y
    du[5] += fix.z
    return du


Flight.u_dot_generalized = _u_dot
