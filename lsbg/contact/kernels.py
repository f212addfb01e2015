"""Compiled contact kernels: tooth-pair forces of the point and the line model.

Both flank sides of a pair are swept by a plane of action (:mod:`lsbg.gear.geometry`),
so a rotation mismatch only moves the contact lines within that plane. With
e_i = sin(delta_b,i), the drive-side mismatch is ``eps = phi1 e1 - phi2 e2``
(wrapped to one base pitch) and the normal approach at a point of a contact
line at distance rho from the apex is ``x = rho cos(beta_p(rho)) eps``
(DESIGN.md §2): the *lever* ``rho cos(beta_p)`` is also the torque arm of the
normal force about gear i per unit e_i. A contact line is the generating curve
turned by Psi; tooth pairs repeat every base pitch Psi_p. Under a mismatch the
pinion's and the gear's lines are eps apart: the point model puts the contact
at their mean, the line model at the pinion's line (the small-deflection
convention of loaded TCA, which makes a linear slice law linear in load).

* The **point model** (the paper's) makes each tooth pair one IMPACT incident
  at the deepest point of its line inside the field of contact. What depends
  only on the line's turn Psi is tabulated (:class:`lsbg.contact.mesh.MeshContact`)
  and interpolated linearly.
* The **line model** cuts the face width into bands (slices). The part of a
  contact line inside band j and inside the field of contact carries the load
  per unit length of :func:`lsbg.contact.law.line_load` at the band's lever;
  a band only partly inside the field counts with that fraction, so a pair
  entering or leaving mesh gains or loses load continuously.

Friction, torques and the tangential force of a normal force at a contact
point are one function (:func:`_point_torques`) for both models.

The kernels take the state (angles [rad], speeds [rad/s]) and three arrays
built by :class:`lsbg.contact.mesh.MeshContact`: ``params`` (scalars, indices
``P_*``), ``sides`` (per flank side, indices ``S_*``) and ``table`` (per side:
the point model's phase table, columns ``T_*``, or the line model's bands,
columns ``B_*``). Everything is SI.
"""

import math

import numpy as np
from llvmlite import ir
from numba import njit, types
from numba.core import cgutils
from numba.extending import intrinsic

from lsbg.contact.law import (
    friction_coefficient_scalar,
    friction_integral_scalar,
    impact_force_scalar,
    line_load_scalar,
)

# --- params: scalars of the pair and the law
(P_E1, P_E2, P_PITCH, P_ORIENTATION, P_COAST_OFFSET, P_COAST_PINION_OFFSET, P_MODEL,
 P_K, P_EXPONENT, P_C_MAX, P_DEPTH, P_MU_S, P_MU_D, P_V_S, P_V_D, P_LINE_K, P_LINE_C,
 P_U12, P_LINE_SHIFT) = range(19)
N_PARAMS = 19
#: Values of ``params[P_MODEL]``.
MODEL_CODES = {"point": 0.0, "line": 1.0}

# --- sides[side]: side 0 = drive, 1 = coast
# U*: components of the rotation axes u_i along the plane's pitch direction p
# and cross direction q; N*: those of N x u_i (the friction lever, line model)
# SEP_*: the line model's separation table (rows of line turns from SEP_FIRST,
# SEP_INV_STEP per radian; SEP_ROWS = 0: conjugate flanks, no table);
# SEP_LEAD: the least mismatch at which the flanks can touch (0 for conjugate
# flanks; negative where a displacement makes them interfere);
# STIFF_*: the line model's slice-stiffness table (the tooth's own compliance:
# rows of line turns from STIFF_FIRST, STIFF_INV_STEP per radian, in the
# table's columns from STIFF_COLUMN; STIFF_ROWS = 0: the uniform bed)
(S_FIRST, S_LAST, S_INV_STEP, S_ROWS, S_PSI_LO, S_PSI_HI, S_U1P, S_U1Q, S_U2P, S_U2Q,
 S_N1P, S_N1Q, S_N2P, S_N2Q, S_SEP_FIRST, S_SEP_INV_STEP, S_SEP_ROWS, S_SEP_LEAD,
 S_STIFF_FIRST, S_STIFF_INV_STEP, S_STIFF_ROWS, S_STIFF_COLUMN) = range(22)
N_SIDE = 22

# --- table[side, row]: point model, per line turn Psi = first + row / inv_step
T_LEVER, T_AA, T_AB, T_BB, T_RADIUS, T_RHO = range(6)
N_PHASE_COLUMNS = 6
# --- table[side, band]: line model, per band of the face width: values at its
# centre, their change across the band (D_*: outer edge minus inner edge), the
# curve's length in the band and its polar angle at the band's edges
(B_RHO, B_LEVER, B_COS, B_SIN, B_D_RHO, B_D_LEVER, B_D_COS, B_D_SIN, B_LENGTH, B_THETA_IN,
 B_THETA_OUT) = range(11)
N_COLUMNS = 11
# ... followed, with a separation table, by two columns per row of line turn:
# the initial separation of the flanks at the band's centre and its change
# across the band (outer edge minus inner edge) [m]; and, with a slice-stiffness
# table, one column per row of line turn from S_STIFF_COLUMN: the band's
# stiffness per unit length over the uniform bed's k_l [-]
B_SEPARATION = N_COLUMNS

# --- details[pair]: one row per tooth pair whose line meets the field
(D_SIDE, D_PHASE, D_LEVER, D_PENETRATION, D_RATE, D_NORMAL, D_MU, D_SLIDE, D_GEAR_TORQUE,
 D_PINION_TORQUE, D_TANGENTIAL, D_RADIUS, D_RHO, D_LENGTH) = range(14)
N_DETAILS = 14

#: How far ahead of the contact lines' motion the point model's phase table
#: is prefetched [s] (see :func:`_prefetch_rows`): about five PyBullet steps.
PREFETCH_TIME = 5e-6
#: Most rows prefetched ahead per tooth pair [-]: PREFETCH_TIME's worth up to
#: about three times the paper's pinion speed (19 rows at the paper's).
PREFETCH_ROWS = 64


@intrinsic
def _prefetch(typingctx, array, side, offset):
    """Hint the CPU to load the cache line at ``array[side].flat[offset]``
    (LLVM's prefetch for a read, high locality); never faults."""

    def codegen(context, builder, signature, args):
        array_type = signature.args[0]
        values = context.make_array(array_type)(context, builder, args[0])
        zero = context.get_constant(types.intp, 0)
        row = cgutils.get_item_pointer(context, builder, array_type, values,
                                       [args[1], zero, zero], wraparound=False)
        address = builder.gep(row, [args[2]])
        i32 = ir.IntType(32)
        prefetch = cgutils.get_or_insert_function(
            builder.module, ir.FunctionType(ir.VoidType(), [address.type, i32, i32, i32]),
            "llvm.prefetch.p0")
        builder.call(prefetch, [address, ir.Constant(i32, 0), ir.Constant(i32, 3),
                                ir.Constant(i32, 1)])
        return context.get_dummy_value()

    return types.void(array, side, offset), codegen


@njit(cache=True)
def _prefetch_rows(table, side, row, ahead, rows):
    """Prefetch the phase table's rows from ``row`` to ``row + ahead``.

    The point model's table holds 20000 rows per base pitch (megabytes), and
    at speed every time step reads rows no earlier step read: without this
    each tooth pair's lookup waits on main memory, as Bullet's step between two
    lookups leaves the hardware prefetcher nothing to follow. Values are
    unchanged; only when they arrive in the cache.
    """
    lo, hi = (row, row + ahead) if ahead > 0 else (row + ahead, row)
    lo = max(lo, 0)
    hi = min(hi + 2, rows)
    columns = table.shape[2]
    for offset in range(lo * columns, hi * columns, 8):  # 8 doubles: one 64-byte line
        _prefetch(table, side, offset)


@njit(cache=True)
def _point_torques(force, lever, aa, ab, bb, w1, w2, sign, v_normal, params, mu):
    """Torques of a normal force at a contact point and of its friction.

    ``aa``, ``ab``, ``bb`` are the products of a = u1 x X and b = u2 x X at the
    point X; the sliding velocity of the pinion on the gear is
    v = w1 a - w2 b, its normal part is ``v_normal`` = lever (w1 e1 - w2 e2)
    (n . (u_i x X) = lever e_i), and friction drags the gear along it. A
    negative ``mu`` means: the friction coefficient at this point's sliding
    speed (the point model); otherwise ``mu`` is the slice's mean coefficient
    along the sliding direction at this point (the line model).

    Returns (gear torque, pinion torque, friction coefficient, sliding speed)
    [N m, N m, -, m/s], torques about the forward axes u2 and u1.
    """
    e1, e2 = params[P_E1], params[P_E2]
    t2 = sign * force * lever * e2
    t1 = -sign * force * lever * e1
    slide2 = w1 * w1 * aa - 2.0 * w1 * w2 * ab + w2 * w2 * bb - v_normal * v_normal
    slide = 0.0
    if slide2 > 0.0:
        slide = math.sqrt(slide2)
        if mu < 0.0:
            mu = friction_coefficient_scalar(slide, params[P_MU_S], params[P_MU_D],
                                             params[P_V_S], params[P_V_D])
        fric = mu * force / slide
        t2 += fric * (w1 * ab - w2 * bb - v_normal * lever * e2)
        t1 -= fric * (w1 * aa - w2 * ab - v_normal * lever * e1)
    return t2, t1, mu, slide


@njit(cache=True)
def _add_pair(gear, pinion, tangential, normal, pairs, deepest, pair_gear, pair_pinion,
              pair_tangential, pair_normal, pair_deepest):
    """A side's sums (torques [N m], forces [N], pairs whose normal force is > 0 [-], the
    deepest approach [m]) with one tooth pair's added, in both models."""
    if pair_normal > 0.0:
        pairs += 1
    if pair_deepest > deepest:
        deepest = pair_deepest
    return (gear + pair_gear, pinion + pair_pinion, tangential + pair_tangential,
            normal + pair_normal, pairs, deepest)


@njit(cache=True)
def _point_side(side, eps, eps_rate, sign, phase, phase_rate, w1, w2, params, sides, table,
                details, count):
    """Sum over the tooth pairs of one side, point model (one IMPACT incident each).

    ``phase_rate`` is how fast the contact lines turn [rad/s]: the rows they
    reach within :data:`PREFETCH_TIME` are prefetched.
    """
    pitch = params[P_PITCH]
    first, last = sides[side, S_FIRST], sides[side, S_LAST]
    inv_step, rows = sides[side, S_INV_STEP], int(sides[side, S_ROWS])
    relative = w1 * params[P_E1] - w2 * params[P_E2]
    phase += math.ceil((first - phase) / pitch) * pitch
    ahead = phase_rate * PREFETCH_TIME * inv_step
    # at most PREFETCH_ROWS either way; none at a NaN speed
    ahead = int(min(max(ahead, -PREFETCH_ROWS), PREFETCH_ROWS)) if ahead == ahead else 0
    gear = pinion = tangential = normal = 0.0
    pairs = np.int64(0)  # not a literal 0 (see _mesh)
    deepest = -math.inf
    while phase <= last:
        pos = (phase - first) * inv_step
        i = int(pos)
        here = phase
        phase += pitch
        if i + 1 >= rows:
            continue
        _prefetch_rows(table, side, i, ahead, rows)
        f = pos - i
        lever = table[side, i, T_LEVER] + f * (table[side, i + 1, T_LEVER] - table[side, i, T_LEVER])
        if lever <= 0.0:
            continue
        x = lever * eps
        xdot = lever * eps_rate
        force = impact_force_scalar(x, xdot, params[P_K], params[P_EXPONENT], params[P_C_MAX],
                                    params[P_DEPTH])
        aa = table[side, i, T_AA] + f * (table[side, i + 1, T_AA] - table[side, i, T_AA])
        ab = table[side, i, T_AB] + f * (table[side, i + 1, T_AB] - table[side, i, T_AB])
        bb = table[side, i, T_BB] + f * (table[side, i + 1, T_BB] - table[side, i, T_BB])
        t2, t1, mu, slide = _point_torques(force, lever, aa, ab, bb, w1, w2, sign,
                                           lever * relative, params, -1.0)
        radius = table[side, i, T_RADIUS] + f * (table[side, i + 1, T_RADIUS] - table[side, i, T_RADIUS])
        gear, pinion, tangential, normal, pairs, deepest = _add_pair(
            gear, pinion, tangential, normal, pairs, deepest, t2, t1, t2 / radius, force, x)
        if details is not None and count < details.shape[0]:
            row = details[count]
            row[D_SIDE], row[D_PHASE], row[D_LEVER] = side, here, lever
            row[D_PENETRATION], row[D_RATE], row[D_NORMAL] = x, xdot, force
            row[D_MU], row[D_SLIDE], row[D_GEAR_TORQUE], row[D_PINION_TORQUE] = mu, slide, t2, t1
            row[D_TANGENTIAL], row[D_RADIUS] = t2 / radius, radius
            row[D_RHO] = table[side, i, T_RHO] + f * (table[side, i + 1, T_RHO] - table[side, i, T_RHO])
            row[D_LENGTH] = 0.0
            count += 1
    return gear, pinion, deepest, tangential, normal, pairs, count


@njit(cache=True)
def _separation(table, side, j, t, sides, here):
    """Initial separation of the flanks in band j at offset t, for a line at
    turn ``here``, interpolated linearly in the turn [m]; and its rate per
    radian of turn [m/rad]."""
    rows = int(sides[side, S_SEP_ROWS])
    position = (here - sides[side, S_SEP_FIRST]) * sides[side, S_SEP_INV_STEP]
    row = int(math.floor(position))
    row = min(max(row, 0), rows - 2)
    w = position - row
    c0 = B_SEPARATION + 2 * row
    s0 = table[side, j, c0] + t * table[side, j, c0 + 1]
    s1 = table[side, j, c0 + 2] + t * table[side, j, c0 + 3]
    return s0 + w * (s1 - s0), (s1 - s0) * sides[side, S_SEP_INV_STEP]


@njit(cache=True)
def _stiffness_factor(table, side, j, sides, here):
    """Stiffness of band j for a line at turn ``here`` over the uniform bed's,
    interpolated linearly in the turn (held at the table's ends) [-]."""
    rows = int(sides[side, S_STIFF_ROWS])
    position = (here - sides[side, S_STIFF_FIRST]) * sides[side, S_STIFF_INV_STEP]
    row = int(math.floor(position))
    row = min(max(row, 0), rows - 2)
    w = min(max(position - row, 0.0), 1.0)
    c0 = int(sides[side, S_STIFF_COLUMN]) + row
    return table[side, j, c0] + w * (table[side, j, c0 + 1] - table[side, j, c0])


@njit(cache=True)
def _line_side(side, eps, eps_rate, sign, phase, phase_rate, w1, w2, params, sides, table,
               details, count, slices):
    """Sum over the tooth pairs and slices of one side, line model."""
    pitch = params[P_PITCH]
    first, last = sides[side, S_FIRST], sides[side, S_LAST]
    bands = int(sides[side, S_ROWS])
    psi_lo, psi_hi = sides[side, S_PSI_LO], sides[side, S_PSI_HI]
    u2p, u2q = sides[side, S_U2P], sides[side, S_U2Q]
    n1p, n1q = sides[side, S_N1P], sides[side, S_N1Q]
    n2p, n2q = sides[side, S_N2P], sides[side, S_N2Q]
    stiffness, damping = params[P_LINE_K], params[P_LINE_C]
    # real flanks: a separation table (conjugate flanks have none)
    real_flanks = sides[side, S_SEP_ROWS] > 0.0
    # the tooth's own compliance: a stiffness per slice and line turn
    own_stiffness = sides[side, S_STIFF_ROWS] > 0.0
    mu_s, mu_d, v_s, v_d = params[P_MU_S], params[P_MU_D], params[P_V_S], params[P_V_D]
    e1, e2 = params[P_E1], params[P_E2]
    # Friction acts across the contact line, along the plane's normal N: the
    # sliding of the relative rotation w1 u1 - w2 u2 about the pitch line,
    # v_N = (w1 (u1 x X) - w2 (u2 x X)) . N = rho (w1 m1 - w2 m2) with
    # m_i = (cos psi, sin psi) . (N x u_i). It vanishes on the pitch line
    # (psi = 0) and grows as rho |slope| |psi| from it.
    slope = w1 * n1q - w2 * n2q
    across = math.copysign(1.0, slope)
    phase += math.ceil((first - phase) / pitch) * pitch
    gear = pinion = tangential = normal = 0.0
    pairs = np.int64(0)  # not a literal 0 (see _mesh)
    deepest = -math.inf
    while phase <= last:
        here = phase
        phase += pitch
        cos_phase, sin_phase = math.cos(here), math.sin(here)
        pair_gear = pair_pinion = pair_tangential = pair_normal = 0.0
        pair_mu = pair_slide = pair_radius = pair_rho = pair_length = 0.0
        pair_deepest = -math.inf
        pair_lever = pair_rate = 0.0
        inside = False
        for j in range(bands):
            a = here + table[side, j, B_THETA_IN]
            b = here + table[side, j, B_THETA_OUT]
            lo, hi = (a, b) if a < b else (b, a)
            # The part of the band's piece of the line inside the field.
            top = hi if hi < psi_hi else psi_hi
            bottom = lo if lo > psi_lo else psi_lo
            if hi > lo:
                if top <= bottom:
                    continue
                fraction = (top - bottom) / (hi - lo)
            elif psi_lo <= lo <= psi_hi:
                fraction = 1.0  # a radial line (beta_p = 0) crosses the band at one psi
            else:
                continue
            inside = True
            # A band cut by the field's edge acts at the middle of its inside
            # part (t from the band's centre, linear within the band).
            t = 0.5 * (top + bottom - a - b) / (b - a) if fraction < 1.0 else 0.0
            lever = table[side, j, B_LEVER] + t * table[side, j, B_D_LEVER]
            x = lever * eps
            xdot = lever * eps_rate
            if real_flanks:
                # the initial separation (modification and displacements),
                # which moves with the line
                gap, gap_rate = _separation(table, side, j, t, sides, here)
                x -= gap
                xdot -= gap_rate * phase_rate
            if x > pair_deepest:
                pair_deepest, pair_lever, pair_rate = x, lever, xdot
            if own_stiffness:
                # stiffness-proportional damping: the slice keeps its damping ratio
                f = _stiffness_factor(table, side, j, sides, here)
                load = line_load_scalar(x, xdot, f * stiffness, f * damping)
            else:
                load = line_load_scalar(x, xdot, stiffness, damping)
            if slices is not None and count < slices.shape[0]:
                slices[count, j] = load
            if load <= 0.0:
                continue
            length = fraction * table[side, j, B_LENGTH]
            force = load * length
            rho = table[side, j, B_RHO] + t * table[side, j, B_D_RHO]
            c_t = table[side, j, B_COS] + t * table[side, j, B_D_COS]
            s_t = table[side, j, B_SIN] + t * table[side, j, B_D_SIN]
            cos_psi = cos_phase * c_t - sin_phase * s_t
            sin_psi = sin_phase * c_t + cos_phase * s_t
            u2x = rho * (cos_psi * u2p + sin_psi * u2q)
            radius = math.sqrt(rho * rho - u2x * u2x)
            t2 = sign * force * lever * e2
            t1 = -sign * force * lever * e1
            # Friction: the slice's mean of mu(|v_N|) sign(v_N) over its psi
            # range (it reverses across the pitch line, with a narrow
            # stiction peak there), from the closed-form integral of mu.
            rate = rho * abs(slope)
            mu = 0.0
            if rate > 0.0:
                if top > bottom:
                    mean = (friction_integral_scalar(abs(top), rate, mu_s, mu_d, v_s, v_d)
                            - friction_integral_scalar(abs(bottom), rate, mu_s, mu_d, v_s, v_d)
                            ) / (top - bottom)
                else:
                    mean = math.copysign(friction_coefficient_scalar(
                        rate * abs(top), mu_s, mu_d, v_s, v_d), top)
                friction = across * mean * force  # on the gear, along +N
                t2 += friction * rho * (cos_psi * n2p + sin_psi * n2q)
                t1 -= friction * rho * (cos_psi * n1p + sin_psi * n1q)
                mu = abs(mean)
            slide = abs(rho * (w1 * (cos_psi * n1p + sin_psi * n1q)
                               - w2 * (cos_psi * n2p + sin_psi * n2q)))
            pair_gear += t2
            pair_pinion += t1
            pair_tangential += t2 / radius
            pair_normal += force
            pair_mu += mu * force
            pair_slide += slide * force
            pair_radius += radius * force
            pair_rho += rho * force
            pair_length += length
        if not inside:
            continue
        gear, pinion, tangential, normal, pairs, deepest = _add_pair(
            gear, pinion, tangential, normal, pairs, deepest, pair_gear, pair_pinion,
            pair_tangential, pair_normal, pair_deepest)
        if details is not None and count < details.shape[0]:
            row = details[count]
            weight = 1.0 / pair_normal if pair_normal > 0.0 else 0.0
            row[D_SIDE], row[D_PHASE], row[D_LEVER] = side, here, pair_lever
            row[D_PENETRATION], row[D_RATE], row[D_NORMAL] = pair_deepest, pair_rate, pair_normal
            row[D_MU], row[D_SLIDE] = pair_mu * weight, pair_slide * weight
            row[D_GEAR_TORQUE], row[D_PINION_TORQUE] = pair_gear, pair_pinion
            row[D_TANGENTIAL], row[D_RADIUS] = pair_tangential, pair_radius * weight
            row[D_RHO], row[D_LENGTH] = pair_rho * weight, pair_length
            count += 1
    return gear, pinion, deepest, tangential, normal, pairs, count


@njit(cache=True)
def _side(side, eps, eps_rate, sign, phase, phase_rate, w1, w2, params, sides, table, details,
          count, slices):
    if params[P_MODEL] == 0.0:
        return _point_side(side, eps, eps_rate, sign, phase, phase_rate, w1, w2, params, sides,
                           table, details, count)
    return _line_side(side, eps, eps_rate, sign, phase, phase_rate, w1, w2, params, sides, table,
                      details, count, slices)


@njit(cache=True)
def _mesh(phi1, phi2, w1, w2, params, sides, table, details, slices):
    """Both flank sides: the drive side when the pinion leads, the coast side otherwise."""
    pitch = params[P_PITCH]
    half = 0.5 * pitch
    e1 = params[P_E1]
    drive = (phi1 * e1 - phi2 * params[P_E2] + half) % pitch - half
    rate = w1 * e1 - w2 * params[P_E2]
    gear = pinion = tangential = normal = 0.0
    pairs = 0
    # np.int64(0), not 0: numba types a counter that starts as a literal first as the
    # literal, and compiles every kernel it is passed to once more for that type (the
    # side kernels three times, not twice)
    count = np.int64(0)
    # The mismatch is the same for every line of a side, so a side whose
    # flanks are apart (eps <= 0) costs nothing more.
    # Where the contact lines sit: the point model (the paper's reproduction)
    # takes the mean of the pinion's and the gear's line (shift 1/2); the line
    # model the pinion's, the small-deflection convention of LTCA, which
    # keeps it linear in load (shift 0).
    shift = params[P_LINE_SHIFT]
    # both sides' lines turn at the rate of the drive side's phase
    phase_rate = params[P_ORIENTATION] * (w1 * e1 - shift * rate)
    coast = (params[P_COAST_OFFSET] - drive + half) % pitch - half
    deepest = drive
    # One call of _side for both sides, the side a run-time integer: numba compiles a
    # function once per constant argument, and LLVM copies a callee into each call
    # site; two calls with the constants 0 and 1 doubled the compile time of every
    # kernel that reaches this one (the same arithmetic either way).
    for side in range(2):
        if side == 0:
            if not drive > sides[0, S_SEP_LEAD]:
                continue
            eps, eps_rate, sign = drive, rate, 1.0
            phase = params[P_ORIENTATION] * (phi1 * e1 - shift * drive)
        else:
            if not coast > 0.0:
                if deepest <= 0.0:
                    deepest = max(deepest, coast)
                continue
            eps, eps_rate, sign = coast, -rate, -1.0
            phase = params[P_ORIENTATION] * ((phi1 + params[P_COAST_PINION_OFFSET]) * e1
                                             + shift * coast)
        g, p, x, t, n, k, count = _side(side, eps, eps_rate, sign, phase, phase_rate, w1, w2,
                                        params, sides, table, details, count, slices)
        if side == 0:
            gear, pinion, deepest, tangential, normal, pairs = g, p, x, t, n, k
        else:
            gear += g
            pinion += p
            tangential += t
            normal += n
            pairs += k
            deepest = max(deepest, x)
    return gear, pinion, deepest, tangential, normal, pairs, count


@njit(cache=True)
def mesh_forces(phi1, phi2, w1, w2, params, sides, table):
    """Contact forces of the mesh at one state (the engines' hot path).

    Parameters
    ----------
    phi1, phi2 : float
        Forward rotations of pinion and gear [rad] (0, 0: drive flanks of
        tooth 0 touch at the mean point).
    w1, w2 : float
        Forward angular speeds [rad/s].
    params, sides, table : numpy.ndarray
        The model, from :class:`lsbg.contact.mesh.MeshContact`.

    Returns
    -------
    gear_torque, pinion_torque : float
        Contact torques about the forward axes u2 and u1 [N m].
    max_penetration : float
        Deepest normal approach of all pairs (<= 0: no contact) [m].
    tangential_force : float
        Contact force on the gear along its circumferential direction at each
        point of action, summed [N].
    normal_force : float
        Sum of the normal forces [N].
    pairs : int
        Tooth pairs carrying load [-].
    """
    # No detail arrays: numba compiles the writes out of this specialisation.
    g, p, x, t, n, k, _ = _mesh(phi1, phi2, w1, w2, params, sides, table, None, None)
    return g, p, x, t, n, k


@njit(cache=True)
def gear_torque(phi1, phi2, w1, w2, params, sides, table):
    """The contact torque on the gear only [N m]: the PyBullet engine's step.

    Parameters and units as :func:`mesh_forces`; returning one float keeps the
    call from Python cheap.
    """
    return _mesh(phi1, phi2, w1, w2, params, sides, table, None, None)[0]


@njit(cache=True)
def mesh_details(phi1, phi2, w1, w2, params, sides, table, details, slices):
    """:func:`mesh_forces` plus one row per tooth pair and the slices' loads.

    Parameters
    ----------
    phi1, phi2, w1, w2, params, sides, table
        As :func:`mesh_forces`.
    details : numpy.ndarray, shape (max_pairs, N_DETAILS)
        Filled with one row per tooth pair whose line meets the field
        (columns ``D_*``), in order: drive side, then coast side.
    slices : numpy.ndarray, shape (max_pairs, bands) or (0, 0)
        Line model: filled with each slice's load per unit length [N/m]
        (0 where the band is outside the field or unloaded).

    Returns
    -------
    tuple
        The values of :func:`mesh_forces` and the number of rows filled.
    """
    return _mesh(phi1, phi2, w1, w2, params, sides, table, details, slices)


@njit(cache=True)
def mesh_series(phi1, phi2, w1, w2, params, sides, table):
    """:func:`mesh_forces` at many states (arrays of equal length).

    Returns
    -------
    numpy.ndarray, shape (n, 6)
        Columns: gear torque, pinion torque [N m], max penetration [m],
        tangential force, normal force [N], tooth pairs carrying load [-].
    """
    out = np.empty((phi1.size, 6))
    for i in range(phi1.size):
        g, p, x, t, n, k = mesh_forces(phi1[i], phi2[i], w1[i], w2[i], params, sides, table)
        out[i, 0], out[i, 1], out[i, 2], out[i, 3], out[i, 4], out[i, 5] = g, p, x, t, n, k
    return out


def compiled_entry(kernel, *args):
    """The compiled entry point of a numba kernel for the types of ``args``.

    Calling it skips numba's dispatch on argument types, about half of the
    ~0.5 µs a call from Python costs; hot Python loops (the PyBullet engine)
    use it. ``kernel(*args)`` is run once to compile it or load it from the
    on-disk cache.
    """
    import numba

    kernel(*args)
    return kernel.overloads[tuple(numba.typeof(a) for a in args)].entry_point
