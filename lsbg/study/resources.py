"""The resource guard: what a design point and a run will cost, estimated before any job.

Part of the configuration check (:mod:`lsbg.study.checks`): a design point's
geometry memory and time from its mesh size (:func:`geometry_cost`), against
the limits (:func:`geometry_problem`); a run's record memory
(:func:`run_memory_gb`), and the line model's and PyBullet's time against
the runtime the simulation rules request (:func:`run_cost_problems`); the
speed sweep's runs (:func:`speed_sweep_problems`); the load against what the
teeth can carry (:func:`load_problems`). The coefficients were measured on a
2-core machine (the calibration is in each constant's comment); they
overestimate rather than under.
"""

from __future__ import annotations

import math
import os

from lsbg.files import number_label
from lsbg.gear.checks import design_value
from lsbg.gear.design import GearPairDesign
from lsbg.study.params import simulation_runtime
from lsbg.study.points import CONTACT_MODELS, speed_labels, speed_sweep_of

__all__ = [
    "RUN_MEMORY_BASE_GB", "RUN_BYTES_PER_INSTANT", "LINE_SECONDS_PER_SLICE",
    "PYBULLET_SECONDS_PER_STEP", "run_memory_gb", "run_cost_problems", "engines_run",
    "GEOMETRY_MEMORY_BASE_GB", "GEOMETRY_BYTES_PER_VERTEX", "GEOMETRY_SECONDS_BASE",
    "GEOMETRY_SECONDS_PER_VERTEX", "GEOMETRY_TIME_EXPONENT", "geometry_cost", "geometry_problem",
    "machine_memory_gb", "memory_limit_gb", "speed_sweep_problems", "STEP_SLOPE",
    "mesh_torque_capacity", "load_problems"
]


#: Memory of a run: a base and the bytes per recorded instant [GB, B]. Measured
#: 160 B per instant and 0.26 GB (``lsbg simulate --engine compiled``, 0.05 s,
#: full rate 2 and 8 MHz: 80 000 and 320 000 instants, 275 and 313 MB peak);
#: three times that per instant covers the other engines' working copies.
RUN_MEMORY_BASE_GB = 0.26
RUN_BYTES_PER_INSTANT = 500


#: Wall time of the line model per slice and simulated second, compiled
#: engine [s]: 1.6, 1.4 and 5.4 s for 20, 200 and 2000 slices over 0.05 s
#: simulated (``lsbg simulate --engine compiled --contact-model line``).
LINE_SECONDS_PER_SLICE = 0.039


#: Wall time of one PyBullet step [s], as tests/benchmarks/bench_dynamics.py measures it.
PYBULLET_SECONDS_PER_STEP = 7.67e-6


def run_memory_gb(samples, duration, full_rate):
    """Instants a run records [-] and the memory it needs [GB].

    Parameters
    ----------
    samples : int
        Output intervals [-].
    duration : float
        Simulated time [s].
    full_rate : float
        Rate of the full-rate record [1/s].
    """
    instants = samples + 1 + duration * full_rate
    return instants, RUN_MEMORY_BASE_GB + instants * RUN_BYTES_PER_INSTANT / 1e9


def run_cost_problems(config):
    """The resource guard of the runs: each run's record against the memory limit,
    and the line model's slices against the runtime the simulation rules request.

    A run records ``samples + 1`` output instants and ``full_rate_hz`` per
    second (:data:`RUN_BYTES_PER_INSTANT`). A line-model step costs in
    proportion to the slices (:data:`LINE_SECONDS_PER_SLICE`, the compiled
    engine, the fastest: the estimate is a lower bound); the rules request
    :func:`lsbg.study.params.simulation_runtime` minutes per run.
    """
    from lsbg.experiments.sensitivity import scaled_contact

    simulation = config["simulation"]
    duration, samples, rate = (simulation["duration_s"], simulation["samples"],
                               simulation["full_rate_hz"])
    problems = []
    instants, need = run_memory_gb(samples, duration, rate)
    limit, source = memory_limit_gb(config)
    if need > limit:
        problems.append(f"simulation.samples = {samples!r}, simulation.full_rate_hz = {rate!r}: "
                        f"each run records {instants:.3g} instants over simulation.duration_s "
                        f"= {duration!r}, about {need:.3g} GB, more than {source} = "
                        f"{limit:.3g} GB")
    budget = simulation_runtime(config)
    slices = [("contact.slices", config["contact"]["slices"], config["contact"]["slices"])]
    slices += [(f"sensitivity.slices[{k}]", factor,
                scaled_contact(config["contact"], "slices", factor)["slices"])
               for k, factor in enumerate(config["sensitivity"].get("slices", []))]
    for key, value, count in slices:
        minutes = LINE_SECONDS_PER_SLICE * count * duration / 60
        if minutes > budget:
            problems.append(f"{key} = {value!r}: a line-model run of {count} slices over "
                            f"simulation.duration_s = {duration!r} takes at least "
                            f"{minutes:.3g} min, more than the {budget} min its rule requests")
    step = simulation["time_step_s"]
    minutes = PYBULLET_SECONDS_PER_STEP * duration / step / 60
    if "pybullet" in engines_run(config) and minutes > budget:
        problems.append(f"simulation.time_step_s = {step!r}: a PyBullet run of "
                        f"{duration / step:.3g} steps over simulation.duration_s = "
                        f"{duration!r} takes about {minutes:.3g} min, more than the {budget} "
                        f"min its rule requests")
    return problems


def engines_run(config):
    """Every engine some run of the study uses."""
    engines = config["engines"]
    run = {engines["sweep"], *(e for model in CONTACT_MODELS
                               for e in engines["reference"].get(model, []))}
    run |= {sweep.get("engine", engines["sweep"]) for sweep in (config.get("sweeps") or {}).values()
            if isinstance(sweep, dict)}
    if speed_sweep_of(config):
        run.add(config["speed_sweep"]["engine"])
    return run


# ----------------------------------------------------------- resource guard
#: Geometry cost model (:func:`geometry_cost`), fitted to ``lsbg geometry``
#: of the paper's design with 37 to 40 000 gear teeth (43 thousand to 7.9
#: million mesh vertices): peak memory = base + per vertex, wall time =
#: base + per vertex * (vertices / 1e6)**(exponent - 1).
GEOMETRY_MEMORY_BASE_GB = 0.29
GEOMETRY_BYTES_PER_VERTEX = 500.0
GEOMETRY_SECONDS_BASE = 3.0
GEOMETRY_SECONDS_PER_VERTEX = 20e-6
GEOMETRY_TIME_EXPONENT = 1.2


def geometry_cost(pair):
    """Estimated peak memory and wall time of ``lsbg geometry`` for a design point.

    The geometry stage builds both solid meshes (:func:`lsbg.solid.solids.gear_mesh`)
    and works on arrays of their vertices and triangles (mass properties,
    STL, the rendered picture); its cost grows with the vertex count and is
    otherwise nearly constant (the exact flanks, ``flanks.nc``). The vertex
    count is estimated without building a mesh, from the same resolution
    (:data:`lsbg.solid.outline.DEFAULT_RESOLUTION`): per member, the lofted sections
    times the teeth times the outline points per tooth, plus on each end
    face a ring of at least z points per ``end_face_step`` of polar angle
    between bore and root and the cap area over ``end_face_step**2``
    (within 15 % of the actual count over 9 to 3000 teeth).

    Calibration: ``lsbg -v geometry --gear-teeth Z`` (the paper's design
    otherwise) on 2 shared cores, 23.5 GB, load average 2-4 (a second series
    at load 3.6-5.7 in its own column); vertices measured from the STL
    triangle counts / 2; the model's figures from the estimated count:

    ======  ========  =========  ========  ===========  =====  ========  =====
    z2      vertices  estimated  wall [s]  (high load)  model  RSS [GB]  model
    ======  ========  =========  ========  ===========  =====  ========  =====
    37      43 k      38 k       3.1                    3.4    0.29      0.31
    1 000   201 k     230 k      4.8                    6.4    0.35      0.41
    3 000   598 k     660 k      10.7                   15     0.53      0.62
    5 000             1.08 M               55           25     0.67      0.83
    10 000  1.98 M    2.16 M     36                     53     1.19      1.37
    20 000  3.96 M    4.30 M     109       151          118    2.14      2.44
    40 000  7.92 M    8.58 M     246       388          267    4.13      4.58
    ======  ========  =========  ========  ===========  =====  ========  =====

    Memory: 0.29 GB + 500 B per vertex; the measured
    slope is 480-495 B per vertex and the same in both series, so with the
    estimate's 8-15 % excess the model stays 7-17 % above the measurement.
    Time: 3 s + 20 us per vertex times (vertices / 1e6)**0.2: the cost per
    vertex rises from 11 to 31 us over the table (meshing and the picture
    outgrow the caches), which the exponent 1.2 follows; the wall time also
    grows with the machine's load (up to 1.6 times above). For
    ``design.gear_teeth: 100000`` (21 M vertices estimated) the model gives
    11 GB and 13 min; the default ``limits.geometry_minutes`` of 10 min
    admits up to about 79 000 teeth on the paper's pinion.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair

    Returns
    -------
    dict
        ``vertices`` ({member: estimated vertex count} [-]), ``memory_gb``
        [GB], ``minutes`` [min].
    """
    from lsbg.solid import outline
    from lsbg.gear.geometry import MEMBERS

    design, resolution = pair.design, outline.DEFAULT_RESOLUTION
    step = resolution.end_face_step
    vertices = {}
    for member in MEMBERS:
        teeth = design.teeth[member - 1]
        sections = outline.section_cone_distances(pair, member, resolution).size
        # the outline counts at the mean point (cheap: one flank of 201 points)
        flank, top, root_arc = outline._outline_counts(pair, member, resolution)
        per_tooth = 2 * (flank + resolution.extension) + top + root_arc
        bore = (design.pinion_bore if member == 1 else design.gear_bore) / 2
        theta_bore = math.asin(min(1.0, bore / design.inner_cone_distance))
        root = design.root_angle(member)
        rings = max(0, math.ceil((root - theta_bore) / step))
        cap = 2 * math.pi * (math.cos(theta_bore) - math.cos(root)) / step**2
        vertices[member] = sections * teeth * per_tooth + 2 * (teeth * rings + cap)
    total = sum(vertices.values())
    seconds = (GEOMETRY_SECONDS_BASE + GEOMETRY_SECONDS_PER_VERTEX * total
               * (total / 1e6) ** (GEOMETRY_TIME_EXPONENT - 1))
    return {"vertices": vertices,
            "memory_gb": GEOMETRY_MEMORY_BASE_GB + GEOMETRY_BYTES_PER_VERTEX * total / 1e9,
            "minutes": seconds / 60}


def geometry_problem(pair, config):
    """The resource guard of a design point's geometry: its :func:`geometry_cost`
    against ``limits.memory_gb`` and ``limits.geometry_minutes``.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    config : dict
        The configuration, defaults filled in.

    Returns
    -------
    tuple of str or None
        (key part, why) of the problem line, naming the teeth of the member
        whose mesh is the larger (they make the point large); None if the
        point is within both limits.
    """
    cost = geometry_cost(pair)
    limit, source = memory_limit_gb(config)
    minutes = config["limits"]["geometry_minutes"]
    beyond = ([f"{cost['memory_gb']:.3g} GB of memory, more than {source} = {limit:.3g} GB"]
              if cost["memory_gb"] > limit else [])
    if cost["minutes"] > minutes:
        beyond.append(f"{cost['minutes']:.3g} min, more than limits.geometry_minutes = "
                      f"{minutes!r}")
    if not beyond:
        return None
    member = max((1, 2), key=lambda m: cost["vertices"][m])
    head = design_value(config, ("pinion_teeth", "gear_teeth")[member - 1])
    why = (f"the geometry ({sum(cost['vertices'].values()):.3g} mesh vertices) would "
           f"need about {' and '.join(beyond)}")
    return head, why


def machine_memory_gb():
    """Physical memory of this machine [GB], or None where the OS does not tell."""
    try:
        return os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") / 1e9
    except (AttributeError, ValueError, OSError):
        return None


def memory_limit_gb(config):
    """The memory a job may use [GB] and the words that name where it comes from."""
    limit = config["limits"].get("memory_gb")
    if limit is not None:
        return limit, "limits.memory_gb"
    machine = machine_memory_gb()
    if machine is None:
        return math.inf, "limits.memory_gb (unset)"
    return machine, "limits.memory_gb (default: this machine's memory)"


def speed_sweep_problems(config):
    """The speed sweep's settings, checked as ``lsbg speed-run`` will use them: one line
    per problem, starting with the ``speed_sweep`` key and its value."""
    from lsbg.dynamics import SimulationSettings
    from lsbg.experiments.speed import speed_keywords, speed_settings

    speed = config["speed_sweep"]
    grid = speed["pinion_speeds_deg_s"]
    problems = []
    angle = speed.get("spiral_angle_deg", config["paper_spiral_angle_deg"])
    if number_label(angle) != number_label(config["paper_spiral_angle_deg"]):
        swept = {number_label(a) for a in config["sweep"]["spiral_angles_deg"]}
        missing = [t for t in speed["traces"]
                   if t not in config["sweep"]["traces"] or number_label(angle) not in swept]
        if missing:
            problems.append(f"speed_sweep.spiral_angle_deg = {angle!r}: no design point of "
                            f"{', '.join(missing)} there (use paper_spiral_angle_deg or an "
                            f"angle of sweep.spiral_angles_deg)")
    try:
        speeds, labels = speed_labels(grid)
    except ValueError as error:
        return [f"speed_sweep.pinion_speeds_deg_s = {grid!r}: {error}"]
    if len(set(labels)) < len(labels):
        problems.append(f"speed_sweep.pinion_speeds_deg_s = {grid!r}: speeds too close to "
                        f"tell apart in file names")
    try:
        base = SimulationSettings.from_config(config["simulation"], engine=speed["engine"])
    except ValueError:
        return problems  # the simulation settings themselves: named by lsbg.dynamics.checks
    teeth = config["design"].get("pinion_teeth", GearPairDesign.pinion_teeth)
    limit, source = memory_limit_gb(config)
    for value in (speeds[0], speeds[-1]):
        at = (f"speed_sweep.pinion_speeds_deg_s = {grid!r}: the run at "
              f"{math.degrees(value):.6g} deg/s")
        try:
            run = speed_settings(base, value, teeth, **speed_keywords(speed))
        except ValueError as error:
            # a setting lsbg.experiments.speed derives for the run ("full_rate = ...: why")
            why = str(error).split(": ", 1)[-1]
            problems.append(f"{at} (speed_sweep.engine = {speed['engine']!r}): {why}")
            continue
        instants, need = run_memory_gb(run.samples, run.duration, run.full_rate)
        if need > limit:
            problems.append(f"{at} records {instants:.3g} instants over {run.duration:.3g} s "
                            f"(speed_sweep.mesh_cycles = {speed['mesh_cycles']!r}, "
                            f"min_window_s = {speed['min_window_s']!r}, samples_per_mesh = "
                            f"{speed['samples_per_mesh']!r}), about {need:.3g} GB, more than "
                            f"{source} = {limit:.3g} GB")
    return problems


#: Largest slope of the STEP ramp of the pinion speed over its mean slope: the
#: smoothstep 3 s^2 - 2 s^3 rises at most 1.5 times as fast as a straight ramp [-].
STEP_SLOPE = 1.5


def mesh_torque_capacity(pair, contact, model):
    """The gear torque beyond which a contact model certainly leaves its range [N m].

    An upper bound of what the teeth can carry before the contact law stops the
    run (:mod:`lsbg.dynamics`: the approach of a line-model slice beyond
    ``line_approach_limit_mm``, a point contact's penetration beyond its
    depth d): every tooth pair that can be in mesh (the total contact ratio,
    rounded up) carrying its most at once, on a full-face contact line of
    length b / cos(beta_m) for the line model, along the normal at the mean
    point, at the gear's mean pitch radius.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    contact : dict
        The ``contact`` section (paper units).
    model : {"line", "point"}

    Returns
    -------
    float
        [N m].
    """
    d = pair.design
    pairs_in_mesh = math.ceil(float(pair.contact_ratio()["total"]))
    if model == "line":
        per_length = contact["line_stiffness_N_per_mm_um"] * 1e9 * contact[
            "line_approach_limit_mm"] * 1e-3  # [N/m]
        normal = per_length * pairs_in_mesh * d.face_width / math.cos(d.spiral_angle)
    else:
        stiffness = contact["stiffness_N_per_mm1_5"]  # [N/mm^e]
        normal = pairs_in_mesh * stiffness * contact["penetration_depth_mm"] ** contact["exponent"]
    tangential = normal * math.cos(d.mean_normal_pressure_angle) * math.cos(d.spiral_angle)
    return tangential * d.mean_pitch_radius(2)


def load_problems(config, pairs):
    """Loads and pinion speeds no contact model could carry, before any job.

    The gear's peak torque is the load plus its inertia times the largest
    acceleration of the STEP ramp (:data:`STEP_SLOPE` times the final gear
    speed over ``simulation.ramp_time_s``); it must stay below the
    :func:`mesh_torque_capacity` of every contact model the study runs, at every
    design point. The tooth-mesh frequency z1 n must also lie below the
    full-rate record's Nyquist frequency, or the record the verdict rests on
    aliases the mesh itself.

    Parameters
    ----------
    config : dict
        The configuration, defaults filled in.
    pairs : dict
        ``(trace, spiral label) -> GearPair`` of the design points that passed.

    Returns
    -------
    list of str
        One line per problem, naming the key and its value.
    """
    from lsbg.solid.mass import quadrature_mass_properties

    simulation, contact = config["simulation"], config["contact"]
    models = ("line", "point")  # both run at the paper's point (the speed sweep: its own guard)
    speeds = [("simulation.pinion_speed_deg_s", simulation["pinion_speed_deg_s"])]
    torques = [("simulation.load_torque_N_m", simulation["load_torque_N_m"])]
    problems = []
    nyquist = simulation["full_rate_hz"] / 2
    for key, speed in speeds:
        teeth = config["design"].get("pinion_teeth", 9)
        mesh = teeth * speed / 360.0
        if mesh > nyquist:
            problems.append(f"{key} = {speed!r}: its tooth-mesh frequency {mesh:.4g} Hz is beyond "
                            f"the full-rate record's Nyquist frequency {nyquist:.4g} Hz "
                            f"(simulation.full_rate_hz = {simulation['full_rate_hz']!r})")
    ramp = simulation["ramp_time_s"]
    worst = {}  # the problem's key text -> (peak, capacity, where): the tightest point
    for (trace, spiral), pair in pairs.items():
        d = pair.design
        inertia = quadrature_mass_properties(pair, 2).axial_inertia
        for model in models:
            capacity = mesh_torque_capacity(pair, contact, model)
            for key, speed in speeds:
                gear_speed = math.radians(speed) * d.pinion_teeth / d.gear_teeth
                inertial = inertia * STEP_SLOPE * gear_speed / ramp if ramp > 0 else 0.0
                for torque_key, torque in torques:
                    peak = torque + inertial
                    if peak <= capacity:
                        continue
                    culprit = (f"{key} = {speed!r} (with simulation.ramp_time_s = {ramp!r}: "
                               f"{inertial:.3g} N m to accelerate the gear)"
                               if inertial > torque else f"{torque_key} = {torque!r}")
                    if culprit not in worst or capacity < worst[culprit][1]:
                        worst[culprit] = (peak, capacity, f"{model} model, {trace} {spiral} deg")
    for culprit, (peak, capacity, where) in worst.items():
        problems.append(f"{culprit}: the gear's peak torque {peak:.3g} N m is beyond what the "
                        f"teeth can carry, at most {capacity:.3g} N m ({where}) before the "
                        f"contact law stops the run")
    return list(dict.fromkeys(problems))
