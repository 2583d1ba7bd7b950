"""OpenRocket's zero-lift drag for one 54 mm rocket, written out from OpenRocket's own code.

An independent second implementation of the drag estimate hpr-mc takes from OpenRocket
(engine/design/src/aero/drag_estimate.rs), for the test
`a_54_mm_rocket_s_estimate_equals_an_independent_replica_of_openrockets_code`
(engine/design/src/aero/tests.rs). Read from openrocket/openrocket, package
info.openrocket.core.aerodynamics: BarrowmanCalculator (calculateFrictionCD,
calculateFrictionCoefficient, calculateRoughnessCorrection, calculatePressureCD,
calculateBaseCD, calculateStagnationCD), barrowman/SymmetricComponentCalc (the tangent
ogive's zero joint angle), barrowman/FinSetCalc and barrowman/RailButtonCalc.

The rocket: a 5:1 tangent ogive (0.27 m) on a 54 mm body 1.3 m long in all, three square
3 mm fins (root 120 mm, tip 50, span 60, leading-edge sweep 50), two rail buttons 11.2 mm
across and 9.1 mm tall centred 0.5 m and 1.2 m aft of the tip, a 60 um finish. The Reynolds
number is hpr-mc's documented sea-level one (Mach x 340.294 / (1.7894e-5 / 1.225)); with this
finish the friction is roughness-limited at these speeds, where OpenRocket's own (the
flight's speed and air) gives the same. Run: python3 validation/openrocket/or_replica.py
"""
import math
R = 0.027; L = 1.3; Ln = 0.27; Aref = math.pi * R * R
rough = 60e-6
a0 = 340.294; nu0 = 1.7894e-5 / 1.225
def stag(m):
    q = 1 + m*m/4 + m**4/40 if m <= 1 else 1.84 - 0.76/m**2 + 0.166/m**4 + 0.035/m**6
    return 0.85 * q
def base(m): return 0.12 + 0.13*m*m if m <= 1 else 0.25/m
rho = (R*R + Ln*Ln) / (2*R)
def r_og(x): return math.sqrt(rho**2 - (Ln - x)**2) + R - rho
N = 200000; nose_wet = 0.0
for i in range(N):
    x0 = Ln*i/N; x1 = Ln*(i+1)/N; y0 = r_og(x0); y1 = r_og(x1)
    nose_wet += math.pi*(y0 + y1)*math.hypot(x1 - x0, y1 - y0)
body_wet = nose_wet + 2*math.pi*R*(L - Ln)
cr, ct, s, sw, t, nf = 0.12, 0.05, 0.06, 0.05, 0.003, 3
af = (cr + ct)/2*s
mac = 2/3*(cr + ct - cr*ct/(cr + ct))
cos2 = math.cos(math.atan(sw/s))**2
buttons = [(0.5, 0.0112, 0.0091), (1.2, 0.0112, 0.0091)]
dom = [0.0,0.2,0.3,0.4,0.5,0.6,0.7,1.0,1.6,2.0,2.8,100.0]; rng = [1.2,1.22,1.25,1.3,1.4,1.5,1.6,2.1,1.5,1.45,1.33,1.33]
def interp(x):
    for i in range(len(dom)-1):
        if dom[i] <= x <= dom[i+1]:
            return rng[i] + (rng[i+1]-rng[i])*(x-dom[i])/(dom[i+1]-dom[i])
def cd(M):
    re = M*a0/nu0*L
    cf = (1.48e-2 if re < 1e4 else 1/(1.5*math.log(re) - 5.6)**2)
    c1 = 1 - 0.1*M*M; c2 = (1 + 0.15*M*M)**-0.58
    cf *= c1 if M < 0.9 else (c2*(M-0.9)/0.2 + c1*(1.1-M)/0.2 if M < 1.1 else c2)
    rc = 1 - 0.1*M*M if M < 0.9 else (1/(1+0.18*M*M) if M > 1.1 else (1/(1+0.18*1.21))*(M-0.9)/0.2 + (1-0.081)*(1.1-M)/0.2)
    cf = max(cf, 0.032*(rough/L)**0.2*rc)
    fb = (L + 0.0001)/R
    friction = cf*(1 + 1/(2*fb))*body_wet/Aref + cf*(1 + 2*t/mac)*2*af*nf/Aref
    finp = (stag(M)*cos2 + base(M))*nf*t*s/Aref
    b = base(M)  # aft base, full radius
    rb = 0.0
    for x, D, h in buttons:
        rex = M*a0/nu0*x; de = 0.37*x/rex**0.2
        mb = (h - 0.5*de)*M/h if h > de else (h/2)/de*M
        rb += interp(mb)*(mb/M)**2*stag(M)*D*h/Aref
    return friction + finp + b + rb  # tangent ogive: no nose pressure drag below Mach 1
for M in (0.3, 0.6, 0.9):
    print(M, repr(cd(M)))
print("nose wet", nose_wet, "mac", mac)
