"""The figures every RocketPy cross-check records of a flight, in one place.

``flight_figures(env, flight)``: apogee (height above the site, time, position), rail exit,
maximum speed, Mach and dynamic pressure, landing (time, position, vertical speed) and each parachute's
trigger and inflation (time, height, position), as floats for JSON. Heights are above the
site; positions and heights are RocketPy's center of dry mass's.
"""


def f(x):
    return float(x)


def flight_figures(env, flight):
    elev = env.elevation
    events = []
    for t_ev, chute in flight.parachute_events:
        t_in = t_ev + chute.lag
        events.append({
            "parachute": chute.name,
            "trigger_time_s": f(t_ev),
            "inflation_time_s": f(t_in),
            "altitude_agl_at_trigger_m": f(flight.z(t_ev) - elev),
            "x_at_inflation_m": f(flight.x(t_in)),
            "y_at_inflation_m": f(flight.y(t_in)),
            "altitude_agl_at_inflation_m": f(flight.z(t_in) - elev),
        })
    return {
        "apogee_agl_m": f(flight.apogee - elev),
        "apogee_time_s": f(flight.apogee_time),
        "apogee_x_m": f(flight.apogee_x),
        "apogee_y_m": f(flight.apogee_y),
        "rail_exit_time_s": f(flight.out_of_rail_time),
        "rail_exit_speed_m_s": f(flight.out_of_rail_velocity),
        "max_speed_m_s": f(flight.max_speed),
        "max_speed_time_s": f(flight.max_speed_time),
        "max_mach": f(flight.max_mach_number),
        "max_dynamic_pressure_pa": f(flight.max_dynamic_pressure),
        "max_dynamic_pressure_time_s": f(flight.max_dynamic_pressure_time),
        "impact_time_s": f(flight.t_final),
        "impact_x_m": f(flight.x_impact),
        "impact_y_m": f(flight.y_impact),
        "impact_speed_m_s": f(flight.impact_velocity),
        "parachute_events": events,
    }
