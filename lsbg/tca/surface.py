"""The contact search between the real flank surfaces, compiled with numba.

For a pinion rotation phi1, each point X of the pinion's (modified,
displaced) flank fixes the gear rotation phi2(X) at which the gear's
(displaced) flank passes through it. That needs no iteration: taken into the
gear's nominal frame, X has a cone distance R' and a polar angle theta' about
the gear axis, both unchanged by the gear's rotation, and the gear flank
point with those two coordinates is closed form (:meth:`lsbg.gear.geometry.GearPair.flank`:
the plane of action's point (R', psi(theta')) turned about the gear axis), so
phi2(X) is the difference of two azimuths. The gear touches first where it
has to turn furthest, phi2* = max phi2(X); the separation of the flanks at X
is then (phi2* - phi2(X)) times the normal speed of the gear flank per unit
rotation there, |n . (u2 x X)|. This is the classical unloaded TCA on the
exact surfaces (Litvin & Fuentes, *Gear Geometry and Applied Theory*, 2nd
ed., 2004, ch. 9), without the plane-of-action shortcut of the contact
kernels.

:func:`contact_search` runs it over mesh positions and tooth pairs: only the
pinion points whose conjugate contact line is near the tooth pair's current
one can be first to touch (the separation grows with the square of the
distance from the line), so each tooth pair searches a window of the points
sorted by that line's turn, doubled until the first contact lies well inside
it. Everything is SI.
"""

import math

import numpy as np
from numba import njit

# --- geometry[...]: the pair's constants (built by lsbg.tca.analysis.SurfacePair)
(G_U1, G_T1, G_TURN, G_T2, G_A2, G_U2, G_REF2, G_OTHER2, G_P, G_Q) = (
    0, 3, 6, 15, 18, 21, 24, 27, 30, 33)
# SIDE: +1 for the drive flanks, -1 for the coast flanks (the search then
# runs on -phi2, so that first contact is always a maximum); OFFSET1: the
# pinion flank's tooth-thickness offset on that side
# ROOT2: the gear's root angle, for the flank chart's height R (theta - root)
# COS_DELTA_B2, COS_PSI_G2, SIN_PSI_G2: cosines and sine of DELTA_B2 and PSI_G2, so that
# the contact search turns the plane-of-action point without trigonometric calls
# POLAR_SCALE: the curve's polar angle over its circle's (GeneratingCurve.polar_scale)
(G_PSI_G2, G_ROLL2, G_DELTA_B2, G_SIDE, G_S2, G_OFFSET2, G_KIND, G_TAN_BETA, G_RM, G_RHO0,
 G_THETA0, G_BRANCH, G_RC, G_THETA_LO2, G_THETA_HI2, G_R_IN, G_R_OUT, G_GEAR_PITCH, G_RATIO,
 G_S1, G_PINION_PITCH, G_OFFSET1, G_ROOT2, G_COS_DELTA_B2, G_COS_PSI_G2,
 G_SIN_PSI_G2, G_POLAR_SCALE) = range(36, 63)
N_GEOMETRY = 63

# --- per mesh position: outputs of contact_search (columns O_*)
# S*: moments of the region's points in the gear frame (true size); C*: in the
# gear flank's chart (cone distance R, height h above the root cone)
(O_PHI2, O_TOOTH, O_POINT, O_COUNT, O_SX, O_SY, O_SZ, O_SXX, O_SXY, O_SXZ, O_SYY, O_SYZ, O_SZZ,
 O_TOE, O_HEEL, O_TIP, O_ROOT, O_R2, O_THETA2, O_WINDOW, O_CR, O_CH, O_CRR, O_CRH,
 O_CHH) = range(25)
N_OUT = 25
#: Edges of the gear flank a contact region can reach, in the order of O_TOE..O_ROOT.
EDGES = ("toe", "heel", "tip", "root")


@njit(cache=True)
def _curve_angle(rho, g):
    """Polar angle theta_c(rho) of the generating curve [rad]."""
    if g[G_KIND] == 0.0:
        return g[G_TAN_BETA] * math.log(rho / g[G_RM])
    rho0, rc = g[G_RHO0], g[G_RC]
    c = (rho * rho + rho0 * rho0 - rc * rc) / (2.0 * rho * rho0)
    c = min(1.0, max(-1.0, c))
    return g[G_POLAR_SCALE] * (g[G_THETA0] + g[G_BRANCH] * math.acos(c))


@njit(cache=True)
def gear_rotation(x, y, z, g):
    """Gear rotation at which the gear's flank (of the pair's side) passes through a point.

    Parameters
    ----------
    x, y, z : float
        The point in the mesh frame [m].
    g : numpy.ndarray
        The pair's constants (``G_*``).

    Returns
    -------
    phi2 : float
        Gear rotation [rad], unwrapped (any tooth); NaN where the gear has no
        flank (outside its face or its profile).
    rho, theta : float
        Cone distance [m] and polar angle about the gear axis [rad] of the
        point in the gear's frame.
    nx, ny, nz : float
        u2 x X in the gear's nominal frame, for the normal speed [m].
    px, py, pz : float
        The point in the gear's nominal frame [m].
    """
    # into the gear's nominal frame: Rg^T (X - t2)
    dx, dy, dz = x - g[G_T2], y - g[G_T2 + 1], z - g[G_T2 + 2]
    t = G_TURN
    px = g[t] * dx + g[t + 3] * dy + g[t + 6] * dz
    py = g[t + 1] * dx + g[t + 4] * dy + g[t + 7] * dz
    pz = g[t + 2] * dx + g[t + 5] * dy + g[t + 8] * dz
    rho = math.sqrt(px * px + py * py + pz * pz)
    c = min(1.0, max(-1.0, (px * g[G_A2] + py * g[G_A2 + 1] + pz * g[G_A2 + 2]) / rho))
    theta = math.acos(c)
    u0, u1, u2 = g[G_U2], g[G_U2 + 1], g[G_U2 + 2]
    nx, ny, nz = u1 * pz - u2 * py, u2 * px - u0 * pz, u0 * py - u1 * px
    if not (g[G_THETA_LO2] <= theta <= g[G_THETA_HI2] and g[G_R_IN] <= rho <= g[G_R_OUT]):
        return math.nan, rho, theta, nx, ny, nz, px, py, pz
    # roll angle chi: cos(theta) = cos(delta_b) cos(chi), so cos(delta_b) sin(chi) =
    # sqrt(cos^2 delta_b - cos^2 theta), exact near the base cone (Sterbenz) and
    # free of trigonometric calls, which bound this kernel's cost
    cos_b = g[G_COS_DELTA_B2]
    product = (cos_b - c) * (cos_b + c)
    if product > 0.0:
        sin_b_chi = math.sqrt(product)
        chi = math.atan(sin_b_chi / c) if c > 0.0 else math.atan2(sin_b_chi, c)
        cos_chi, sin_chi = c / cos_b, sin_b_chi / cos_b
    else:  # inside the base cone: the flank's root end, chi = 0
        chi, cos_chi, sin_chi = 0.0, 1.0, 0.0
    roll = g[G_ROLL2]
    psi = g[G_PSI_G2] + roll * chi
    turn = -(psi - _curve_angle(rho, g)) / g[G_S2] + g[G_OFFSET2]
    # cos and sin of psi = psi_g + roll chi by the addition theorem
    cpg, spg = g[G_COS_PSI_G2], g[G_SIN_PSI_G2]
    cp = cpg * cos_chi - roll * spg * sin_chi
    sp = spg * cos_chi + roll * cpg * sin_chi
    fx = cp * g[G_P] + sp * g[G_Q]
    fy = cp * g[G_P + 1] + sp * g[G_Q + 1]
    fz = cp * g[G_P + 2] + sp * g[G_Q + 2]
    # the point's azimuth less the flank point's, as one atan2 of the two directions
    flank_ref = fx * g[G_REF2] + fy * g[G_REF2 + 1] + fz * g[G_REF2 + 2]
    flank_other = fx * g[G_OTHER2] + fy * g[G_OTHER2 + 1] + fz * g[G_OTHER2 + 2]
    point_ref = px * g[G_REF2] + py * g[G_REF2 + 1] + pz * g[G_REF2 + 2]
    point_other = px * g[G_OTHER2] + py * g[G_OTHER2 + 1] + pz * g[G_OTHER2 + 2]
    azimuth = math.atan2(point_other * flank_ref - point_ref * flank_other,
                         point_ref * flank_ref + point_other * flank_other)
    return azimuth - turn, rho, theta, nx, ny, nz, px, py, pz


@njit(cache=True)
def _rotation(axis, angle):
    """Rodrigues matrix of a right-handed turn about a unit axis."""
    c, s = math.cos(angle), math.sin(angle)
    k0, k1, k2 = axis[0], axis[1], axis[2]
    m = np.empty((3, 3))
    m[0, 0] = c + k0 * k0 * (1 - c)
    m[0, 1] = k0 * k1 * (1 - c) - k2 * s
    m[0, 2] = k0 * k2 * (1 - c) + k1 * s
    m[1, 0] = k1 * k0 * (1 - c) + k2 * s
    m[1, 1] = c + k1 * k1 * (1 - c)
    m[1, 2] = k1 * k2 * (1 - c) - k0 * s
    m[2, 0] = k2 * k0 * (1 - c) - k1 * s
    m[2, 1] = k2 * k1 * (1 - c) + k0 * s
    m[2, 2] = c + k2 * k2 * (1 - c)
    return m


@njit(cache=True)
def _point_rotation(m, points, normals, i, g, kinematic):
    """phi2 of pinion point i turned by m (times the side's sign, wrapped to
    the tooth nearest ``kinematic``, which carries the same sign), its normal
    speed and gear-frame coordinates."""
    bx, by, bz = points[i, 0], points[i, 1], points[i, 2]
    x = m[0, 0] * bx + m[0, 1] * by + m[0, 2] * bz + g[G_T1]
    y = m[1, 0] * bx + m[1, 1] * by + m[1, 2] * bz + g[G_T1 + 1]
    z = m[2, 0] * bx + m[2, 1] * by + m[2, 2] * bz + g[G_T1 + 2]
    phi, rho, theta, nx, ny, nz, px, py, pz = gear_rotation(x, y, z, g)
    if phi != phi:
        return phi, 0.0, rho, theta, px, py, pz
    phi *= g[G_SIDE]
    pitch = g[G_GEAR_PITCH]
    phi -= pitch * math.floor((phi - kinematic) / pitch + 0.5)
    # normal speed |n . (u2 x X)| in the gear's frame: n turned by m, then Rg^T
    ax, ay, az = normals[i, 0], normals[i, 1], normals[i, 2]
    mx = m[0, 0] * ax + m[0, 1] * ay + m[0, 2] * az
    my = m[1, 0] * ax + m[1, 1] * ay + m[1, 2] * az
    mz = m[2, 0] * ax + m[2, 1] * ay + m[2, 2] * az
    t = G_TURN
    gx = g[t] * mx + g[t + 3] * my + g[t + 6] * mz
    gy = g[t + 1] * mx + g[t + 4] * my + g[t + 7] * mz
    gz = g[t + 2] * mx + g[t + 5] * my + g[t + 8] * mz
    return phi, abs(gx * nx + gy * ny + gz * nz), rho, theta, px, py, pz


@njit(cache=True)
def _refined_maximum(phi1, tooth, point, value, n_face, n_profile, points, normals, g, kinematic):
    """The first-contact rotation between the grid points: the maximum of the
    quadratic through the 3 x 3 points around the best one.

    Without it the grid's spacing h would leave the first contact short by
    the separation at h/2 from it, kappa h^2/8 (about 0.1 µm, 2 µrad of
    gear rotation, at 0.08 mm); the quadratic's maximum is exact for a
    quadratic separation. Kept at the grid value where the stencil leaves
    the grid or the gear's flank, or where the separation is not curved in
    both directions (line contact).
    """
    face, profile = point // n_profile, point % n_profile
    if face == 0 or profile == 0 or face == n_face - 1 or profile == n_profile - 1:
        return value
    m = _rotation(g[G_U1:G_U1 + 3], phi1 + tooth * g[G_PINION_PITCH])
    f = np.empty((3, 3))
    for a in range(3):
        for b in range(3):
            i = (face + a - 1) * n_profile + profile + b - 1
            phi, _, _, _, _, _, _ = _point_rotation(m, points, normals, i, g, kinematic)
            if phi != phi:
                return value
            f[a, b] = phi
    fx, fy = 0.5 * (f[2, 1] - f[0, 1]), 0.5 * (f[1, 2] - f[1, 0])
    fxx, fyy = f[2, 1] - 2 * f[1, 1] + f[0, 1], f[1, 2] - 2 * f[1, 1] + f[1, 0]
    fxy = 0.25 * (f[2, 2] - f[2, 0] - f[0, 2] + f[0, 0])
    det = fxx * fyy - fxy * fxy
    if not (fxx < 0.0 and det > 0.0):
        return value
    dx = -(fyy * fx - fxy * fy) / det
    dy = -(fxx * fy - fxy * fx) / det
    if abs(dx) > 1.0 or abs(dy) > 1.0:
        return value
    return max(value, f[1, 1] + 0.5 * (fx * dx + fy * dy))


@njit(cache=True)
def contact_search(pinion_angles, teeth, points, normals, line_turn, order, grid_shape, g,
                   window, marking, edge_tolerance, raster, raster_limits, out):
    """First contact, separation and contact region at each mesh position.

    Parameters
    ----------
    pinion_angles : numpy.ndarray, shape (n,)
        Pinion rotations [rad].
    teeth : numpy.ndarray of int
        Pinion teeth searched (0: the reference tooth; j turns by 2 pi j / z1).
    points, normals : numpy.ndarray, shape (m, 3)
        The modified pinion flank of tooth 0 in its body frame [m] and its
        outward unit normals [-], a (face x profile) grid flattened.
    line_turn : numpy.ndarray, shape (m,)
        Turn Psi of the conjugate contact line through each point [rad].
    order : numpy.ndarray of int, shape (m,)
        Points sorted by ``line_turn``.
    grid_shape : (int, int)
        Points across the face and along the profile.
    g : numpy.ndarray
        The pair's constants (``G_*``).
    window : float
        First half-width of the search window in line turn [rad].
    marking : float
        Marking-compound thickness: the contact region is where the
        separation is at most this [m].
    edge_tolerance : numpy.ndarray, shape (2,)
        A region point this close to the gear's face ends [m] or its
        profile's ends [rad of polar angle] reaches that edge.
    raster : numpy.ndarray, shape (a, b)
        Least separation over all positions on a gear-flank grid (cone
        distance x polar angle), updated in place [m] (start with inf).
    raster_limits : numpy.ndarray, shape (4,)
        R_lo, R_hi [m], theta_lo, theta_hi [rad] of the raster.
    out : numpy.ndarray, shape (n, N_OUT)
        Filled per position (columns ``O_*``): first-contact gear rotation
        (times the side's sign),
        tooth and point, the first-contact pair's region (point count, first
        and second moments of its points in the gear frame), the edge flags
        of every pair's region, and the contact point's gear coordinates.
    """
    n_face, n_profile = grid_shape
    m_points = points.shape[0]
    sorted_turn = line_turn[order]
    u1 = g[G_U1:G_U1 + 3]
    # the first pass's points: tooth, index, phi2, normal speed, R, theta, gear-frame point
    kept = np.empty((teeth.size * m_points, 9))
    r_lo, r_hi, t_lo, t_hi = raster_limits[0], raster_limits[1], raster_limits[2], raster_limits[3]
    ra, rb = raster.shape
    for k in range(pinion_angles.size):
        phi1 = pinion_angles[k]
        kinematic = g[G_SIDE] * phi1 * g[G_RATIO]
        half = window
        while True:
            # first pass: every point of the window, kept for the second
            best = -math.inf
            # not literals: _refined_maximum would be compiled for them too (see _mesh)
            best_tooth, best_point = np.int64(-1), np.int64(-1)
            at_edge = False
            seen = 0
            for tooth in teeth:
                turn = phi1 + tooth * g[G_PINION_PITCH]
                psi = g[G_S1] * (turn + g[G_OFFSET1])
                lo = np.searchsorted(sorted_turn, psi - half)
                hi = np.searchsorted(sorted_turn, psi + half)
                if hi <= lo:
                    continue
                m = _rotation(u1, turn)
                for s in range(lo, hi):
                    i = order[s]
                    phi, speed, rho, theta, px, py, pz = _point_rotation(m, points, normals, i, g,
                                                                         kinematic)
                    if phi != phi:
                        continue
                    kept[seen, 0], kept[seen, 1], kept[seen, 2] = tooth, i, phi
                    kept[seen, 3], kept[seen, 4], kept[seen, 5] = speed, rho, theta
                    kept[seen, 6], kept[seen, 7], kept[seen, 8] = px, py, pz
                    seen += 1
                    if phi > best:
                        best, best_tooth, best_point = phi, tooth, i
                        at_edge = abs(line_turn[i] - psi) > 0.6 * half
            if best_point < 0 or not at_edge or half > 4.0:
                break
            half *= 2.0
        row = out[k]
        row[:] = 0.0
        row[O_TOOTH], row[O_POINT], row[O_WINDOW] = best_tooth, best_point, half
        if best_point < 0:
            row[O_PHI2] = math.nan
            continue
        best = _refined_maximum(phi1, best_tooth, best_point, best, n_face, n_profile, points,
                                normals, g, kinematic)
        row[O_PHI2] = best
        # second pass: separations, region moments, edges, raster
        count = 0
        for j in range(seen):
            tooth, i, phi = int(kept[j, 0]), int(kept[j, 1]), kept[j, 2]
            speed, rho, theta = kept[j, 3], kept[j, 4], kept[j, 5]
            px, py, pz = kept[j, 6], kept[j, 7], kept[j, 8]
            gap = (best - phi) * speed
            if tooth == best_tooth and i == best_point:
                row[O_R2], row[O_THETA2] = rho, theta
            ia = int((rho - r_lo) / (r_hi - r_lo) * ra)
            ib = int((theta - t_lo) / (t_hi - t_lo) * rb)
            if 0 <= ia < ra and 0 <= ib < rb and gap < raster[ia, ib]:
                raster[ia, ib] = gap
            if gap > marking:
                continue
            face, profile = i // n_profile, i % n_profile
            if face == 0 or rho - g[G_R_IN] < edge_tolerance[0]:
                row[O_TOE] = 1.0
            if face == n_face - 1 or g[G_R_OUT] - rho < edge_tolerance[0]:
                row[O_HEEL] = 1.0
            # the pinion's profile ends meet the gear's other end
            if profile == 0 or g[G_THETA_HI2] - theta < edge_tolerance[1]:
                row[O_TIP] = 1.0
            if profile == n_profile - 1 or theta - g[G_THETA_LO2] < edge_tolerance[1]:
                row[O_ROOT] = 1.0
            if tooth != best_tooth:
                continue  # the ellipse is the first-contact pair's
            count += 1
            row[O_SX] += px
            row[O_SY] += py
            row[O_SZ] += pz
            row[O_SXX] += px * px
            row[O_SXY] += px * py
            row[O_SXZ] += px * pz
            row[O_SYY] += py * py
            row[O_SYZ] += py * pz
            row[O_SZZ] += pz * pz
            h = rho * (theta - g[G_ROOT2])
            row[O_CR] += rho
            row[O_CH] += h
            row[O_CRR] += rho * rho
            row[O_CRH] += rho * h
            row[O_CHH] += h * h
        row[O_COUNT] = count
    return out


@njit(cache=True)
def point_separations(pinion_angles, points, normals, g):
    """Separation of the flanks at pinion points at the kinematic gear position.

    Parameters
    ----------
    pinion_angles : numpy.ndarray, shape (m,)
        Pinion rotation at which each point is taken [rad].
    points, normals : numpy.ndarray, shape (m, 3)
        Points of the modified pinion flank in its body frame [m], outward
        unit normals [-].
    g : numpy.ndarray
        The pair's constants (``G_*``).

    Returns
    -------
    numpy.ndarray, shape (m,)
        (phi2_kinematic - phi2(X)) |n . (u2 x X)| [m]: the normal gap the
        gear must close from its kinematic position to touch at X (negative:
        the flanks interfere there); NaN where the gear has no flank.
    """
    out = np.empty(pinion_angles.size)
    u1 = g[G_U1:G_U1 + 3]
    # A grid of (line turn x cone distance) gives each row's points one pinion
    # rotation: its matrix is built once per run of equal angles, not per point (the
    # same matrix, bit for bit; the kernel 12 % faster on the line model's grids)
    m = _rotation(u1, pinion_angles[0]) if pinion_angles.size else np.empty((3, 3))
    for i in range(pinion_angles.size):
        if i > 0 and pinion_angles[i] != pinion_angles[i - 1]:
            m = _rotation(u1, pinion_angles[i])
        kinematic = g[G_SIDE] * pinion_angles[i] * g[G_RATIO]
        phi, speed, _, _, _, _, _ = _point_rotation(m, points, normals, i, g, kinematic)
        out[i] = (kinematic - phi) * speed
    return out
