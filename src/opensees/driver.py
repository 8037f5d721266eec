# ---------------------------------------------------------------------------------------------
# The driver: builds the OpenSees model from MODEL (above), runs it with and without contact and
# prints the headline numbers as JSON (the fields of pounding's summary.json). Written by
# `pounding export opensees`; the same text for every scenario, only MODEL changes.
# ---------------------------------------------------------------------------------------------
import argparse
import ctypes
import importlib.util
import json
import math
import os
import sys
import time


def import_opensees():
    """Import openseespy. Its Linux wheel ships liblapack.so.3 and libblas.so.3 in
    openseespylinux/lib, but the RUNPATH of opensees.so does not reach libblas from liblapack:
    on a machine without a system BLAS the import fails. Loading the bundled libraries first
    (RTLD_GLOBAL) satisfies it."""
    try:
        import openseespy.opensees as ops
        return ops
    except Exception as first:
        spec = importlib.util.find_spec("openseespylinux")
        if spec is None or spec.origin is None:
            raise first
        lib = os.path.join(os.path.dirname(spec.origin), "lib")
        for name in ("libquadmath.so.0", "libgfortran.so.4", "libblas.so.3", "liblapack.so.3"):
            path = os.path.join(lib, name)
            if os.path.exists(path):
                ctypes.CDLL(path, mode=ctypes.RTLD_GLOBAL)
        import openseespy.opensees as ops
        return ops


def node_tag(s, k):
    """Node k (0 = base) of structure s (0 or 1)."""
    return 100000 * (s + 1) + k


class StepFailed(Exception):
    pass


class Model:
    def __init__(self, ops, model, dt, duration, contact):
        self.ops, self.m, self.dt, self.duration, self.contact = ops, model, dt, duration, contact
        self.heights = []  # per structure: node heights (0 = base)
        self.track = []  # per structure: [(height, node)] of every tracked height
        self.fe_periods = [[], []]  # periods of the FE modes (modal damping only), s
        self.links = [[], []]  # per shear building: (element, node below, node above) per storey
        self.warnings = []

    # -- model -------------------------------------------------------------------------------
    def build(self):
        ops, m = self.ops, self.m
        ops.wipe()
        ops.model("basic", "-ndm", 2, "-ndf", 3)
        ops.geomTransf("Linear", 1)
        ele = 1
        self.struct_eles, self.struct_nodes = [], []
        for s, st in enumerate(m["structures"]):
            hs = st["node_heights"]
            self.heights.append(hs)
            nodes = [node_tag(s, k) for k in range(len(hs))]
            self.struct_nodes.append(nodes[1:])
            eles = []
            # both structures stand on the same vertical line: OpenSees has no geometric
            # contact, so the contact elements join coincident nodes (zero length); the gap is
            # in the contact material
            for k, h in enumerate(hs):
                ops.node(nodes[k], 0.0, h)
            ops.fix(nodes[0], 1, 1, 1)
            if st["kind"] == "cantilever":
                for k in range(1, len(hs)):
                    ops.fix(nodes[k], 0, 1, 0)  # no axial deformation
                for k in range(1, len(hs)):
                    # E = EI, A = Iz = 1: only EI matters with the axial DOFs fixed;
                    # -cMass: consistent (Hermitian) mass of m per unit length
                    ops.element("elasticBeamColumn", ele, nodes[k - 1], nodes[k], 1.0,
                                st["bending_stiffness"], 1.0, 1,
                                "-mass", st["mass_per_length"], "-cMass")
                    eles.append(ele)
                    ele += 1
            else:  # shear building: floor masses, storey springs (twoNodeLink, shear direction)
                for k in range(1, len(hs)):
                    ops.fix(nodes[k], 0, 1, 1)  # rigid floors: no rotation, no axial motion
                    ops.mass(nodes[k], st["floor_masses"][k - 1], 0.0, 0.0)
                bw = st.get("bouc_wen")
                links = []
                for k in range(1, len(hs)):
                    mat = 1000 + ele
                    if bw:
                        # a yielding storey: OpenSees' BoucWen with the program's law mapped
                        # onto it (its Z = d_y z in metres: beta and gamma divided by d_y^n)
                        b = bw[k - 1]
                        ops.uniaxialMaterial("BoucWen", mat, b["alpha"], b["ko"], b["n"],
                                             b["gamma"], b["beta"], b["a0"], b["delta_a"],
                                             b["delta_nu"], b["delta_eta"], b["tolerance"],
                                             b["max_iterations"])
                    else:
                        ops.uniaxialMaterial("Elastic", mat, st["storey_stiffnesses"][k - 1])
                    # local x vertical (node to node), local y = shear: -dir 2; rotations are
                    # fixed, so the link is a pure storey spring k_j
                    ops.element("twoNodeLink", ele, nodes[k - 1], nodes[k], "-mat", mat,
                                "-dir", 2, "-doRayleigh")
                    eles.append(ele)
                    links.append((ele, nodes[k - 1], nodes[k]))
                    ele += 1
                self.links[s] = links
            self.struct_eles.append(eles)
            track = []
            for h in st["tracked_heights"]:
                k = min(range(len(hs)), key=lambda i: abs(hs[i] - h))
                track.append((h, nodes[k]))
            self.track.append(track)
        self.level_nodes = []
        for lv in m["levels"]:
            pair = []
            for s in range(2):
                hs = self.heights[s]
                k = min(range(len(hs)), key=lambda i: abs(hs[i] - lv["height"]))
                pair.append(node_tag(s, k))
            self.level_nodes.append(pair)
        self.contact_eles = []
        if self.contact:
            for j, lv in enumerate(m["levels"]):
                tag = 5000 + j
                self.material(tag, lv)
                # deformation = u(structure 2) - u(structure 1) = -(w1 - w2): compression is
                # the structures approaching, the gap is the material's (negative) gap
                ops.element("zeroLength", 9000 + j, self.level_nodes[j][0], self.level_nodes[j][1],
                            "-mat", tag, "-dir", 1)
                self.contact_eles.append(9000 + j)
        self.rayleigh()
        self.loads()

    def material(self, tag, lv):
        ops, c = self.ops, lv["material"]
        kind = c["type"]
        if kind == "ElasticMultiLinear":
            ops.uniaxialMaterial("ElasticMultiLinear", tag, "-strain", *c["strain"],
                                 "-stress", *c["stress"])
        elif kind == "ElasticPPGap":
            ops.uniaxialMaterial("ElasticPPGap", tag, c["k"], c["fy"], c["gap"])
        elif kind == "ViscoelasticGap":
            ops.uniaxialMaterial("ViscoelasticGap", tag, c["k"], c["c"], c["gap"])
        elif kind == "Hertzdamp":
            ops.uniaxialMaterial("Hertzdamp", tag, c["k"], c["xi_norm"], c["gap"], 1.5)
        elif kind == "JankowskiImpact":
            ops.uniaxialMaterial("JankowskiImpact", tag, c["k"], c["xi"], c["m_eff"], c["gap"], 1.5)
        else:
            raise SystemExit("unknown contact material " + kind)

    def rayleigh(self):
        """Rayleigh damping C = a0 M + a1 K on each structure that has it, never on the contact
        elements (regions, defined with the model, before the analysis)."""
        ops, m = self.ops, self.m
        for s, st in enumerate(m["structures"]):
            d = st["damping"]
            if d["kind"] != "rayleigh":
                continue
            # one region of the structure's elements: a region also sets the factors of the
            # nodes of its elements (so a second region of the nodes alone would be undone);
            # α_M acts on the element mass (cantilever) and the floor masses (building); β_K on
            # the *initial* stiffness (betaK0): the program's damping is that of the initial
            # stiffness, constant in time, also when storeys yield (the same for elastic ones)
            ops.region(s + 1, "-ele", *self.struct_eles[s], "-rayleigh",
                       d["alpha_m"], 0.0, d["beta_k"], 0.0)

    def damping(self):
        """Modal damping, after the analysis is defined (eigen and modalDampingQ act on it)."""
        ops, m = self.ops, self.m
        modal = [st["damping"] for st in m["structures"]]
        if not any(d["kind"] == "modal" for d in modal):
            return
        # modal damping: every mode of the FE model (all of them, by the full eigensolver),
        # each assigned to the structure it moves and given that structure's ratio for its
        # mode number (the ratio of the last mode given beyond the modes the program keeps)
        ndof = sum(len(n) * (2 if st["kind"] == "cantilever" else 1)
                   for n, st in zip(self.struct_nodes, m["structures"]))
        lam = ops.eigen("-fullGenLapack", ndof)
        count = [0, 0]
        ratios = []
        for i in range(len(lam)):
            share = []
            for s in range(2):
                e = 0.0
                for n in self.struct_nodes[s]:
                    e += sum(v * v for v in ops.nodeEigenvector(n, i + 1))
                share.append(e)
            s = 0 if share[0] >= share[1] else 1
            d = modal[s]
            if d["kind"] == "modal":
                r = d["ratios"]
                ratios.append(r[min(count[s], len(r) - 1)])
            else:
                ratios.append(0.0)  # that structure is damped by Rayleigh
            count[s] += 1
            self.fe_periods[s].append(2.0 * math.pi / math.sqrt(lam[i]))
        # the "quick" form: modal damping forces in the residual, not in the (banded) tangent,
        # whose dense modal terms a band solver would drop; Newton converges all the same
        ops.modalDampingQ(*ratios)

    def loads(self):
        """Ground motion as nodal loads -M r a_g(t) through a Plain pattern with a Path series
        (never UniformExcitation: with element mass it applies the load twice in OpenSees
        3.7.1), and the air-damping load -c_a r v_g(t) the same way."""
        ops, m, g = self.ops, self.m, self.m["ground"]
        if g["kind"] == "none":
            return
        dt = self.dt
        n = int(math.ceil(self.duration / dt + 1e-9)) + 2
        if g["kind"] == "harmonic":
            pga, w = g["pga"], g["omega"]
            acc = [-pga * math.sin(w * k * dt) for k in range(n)]
            vel = [pga / w * math.cos(w * k * dt) for k in range(n)]
            sdt = dt
        else:
            acc, vel, sdt = g["accel"], g.get("velocity"), g["dt"]
        ops.timeSeries("Path", 1, "-dt", sdt, "-values", *acc)
        ops.pattern("Plain", 1, 1)
        self.nodal_inertia(1.0, lambda st: True)
        if any(st.get("air_damping", 0.0) > 0.0 for st in m["structures"]):
            ops.timeSeries("Path", 2, "-dt", sdt, "-values", *vel)
            ops.pattern("Plain", 2, 2)
            # air drag c_a (w' + v_g) per unit length: the v_g part is a load, consistent like
            # the inertia (c_a/m times M r)
            self.nodal_inertia(None, lambda st: st.get("air_damping", 0.0) > 0.0)

    def nodal_inertia(self, scale, which):
        ops, m = self.ops, self.m
        for s, st in enumerate(m["structures"]):
            if not which(st):
                continue
            hs = self.heights[s]
            f = [0.0] * len(hs)
            mom = [0.0] * len(hs)
            if st["kind"] == "cantilever":
                q = st["mass_per_length"] if scale is not None else st["air_damping"]
                for k in range(1, len(hs)):
                    le = hs[k] - hs[k - 1]
                    # consistent load of a uniform q: q Le/2 at both ends, and end moments
                    # q Le²/12 (θz = -du/dy for a column along y)
                    f[k - 1] += q * le / 2.0
                    f[k] += q * le / 2.0
                    mom[k - 1] -= q * le * le / 12.0
                    mom[k] += q * le * le / 12.0
            else:
                for k in range(1, len(hs)):
                    f[k] = st["floor_masses"][k - 1]
            for k in range(1, len(hs)):
                ops.load(node_tag(s, k), -f[k], 0.0, -mom[k])

    # -- analysis ------------------------------------------------------------------------------
    def analysis(self):
        ops = self.ops
        ops.wipeAnalysis()
        ops.constraints("Plain")
        ops.numberer("RCM")
        ops.system("BandGeneral")
        ops.test("NormDispIncr", self.m["tolerance"], 50)
        ops.algorithm("Newton")
        ops.integrator("Newmark", 0.5, 0.25)  # average acceleration
        ops.analysis("Transient")

    def try_step(self, h):
        """One step of h; on failure: halve the step down to h/64, then the same with
        ModifiedNewton and KrylovNewton (200 iterations). Returns the number of fallbacks."""
        ops = self.ops
        if ops.analyze(1, h) == 0:
            return 0
        target = ops.getTime() + h  # a failed analyze leaves the last committed state
        for alg in (None, ("ModifiedNewton",), ("KrylovNewton",)):
            if alg is not None:
                ops.algorithm(*alg)
                ops.test("NormDispIncr", self.m["tolerance"], 200)
            sub = h / 2.0
            ok = True
            while ops.getTime() < target - 1e-12 * h:
                step = min(sub, target - ops.getTime())
                if ops.analyze(1, step) == 0:
                    self.observe()
                    continue
                sub /= 2.0
                if sub < h / 64.0:
                    ok = False
                    break
            if alg is not None:
                ops.algorithm("Newton")
                ops.test("NormDispIncr", self.m["tolerance"], 50)
            if ok:
                return 1
        raise StepFailed("step at t = %.6g s failed (Newton, substeps to dt/64, ModifiedNewton, KrylovNewton)" % ops.getTime())

    def observe(self):
        ops = self.ops
        self.observe_storeys()
        w = [[ops.nodeDisp(n, 1) for (_, n) in tr] for tr in self.track]
        for s in range(2):
            for i, x in enumerate(w[s]):
                if abs(x) > self.peaks[s][i]:
                    self.peaks[s][i] = abs(x)
        for j, (n1, n2) in enumerate(self.level_nodes):
            w1, w2 = ops.nodeDisp(n1, 1), ops.nodeDisp(n2, 1)
            lv = self.levels[j]
            lv["peak_w"][0] = max(lv["peak_w"][0], abs(w1))
            lv["peak_w"][1] = max(lv["peak_w"][1], abs(w2))
            lv["max_closing"] = max(lv["max_closing"], w1 - w2)
            delta = w1 - w2 - self.m["levels"][j]["gap"]
            if self.contact:
                f = -ops.eleResponse(self.contact_eles[j], "material", 1, "stress")[0]
                lv["peak_force"] = max(lv["peak_force"], f)
                t = ops.getTime()
                if delta > 0.0:
                    lv["max_penetration"] = max(lv["max_penetration"], delta)
                    if not lv["open"]:
                        lv["impacts"] += 1
                        lv["open"] = True
                    lv["contact_time"] += t - self.last_t
                else:
                    lv["open"] = False
        self.last_t = ops.getTime()

    def observe_storeys(self):
        """Per storey of a shear building: peak |drift| (u above - u below), peak |V| of the
        link, the signed drift, and the work of V over the drift (trapezoidal between step ends)
        for the hysteretic energy."""
        ops = self.ops
        for s, links in enumerate(self.links):
            for j, (ele, below, above) in enumerate(links):
                d = ops.nodeDisp(above, 1) - ops.nodeDisp(below, 1)
                # the link's own deformation and force (consistent signs: the material's strain
                # and stress)
                e = ops.eleResponse(ele, "basicDeformation")[0]
                v = ops.eleResponse(ele, "basicForce")[0]
                r = self.storeys[s][j]
                r["peak_drift"] = max(r["peak_drift"], abs(d))
                r["peak_force"] = max(r["peak_force"], abs(v))
                r["residual_drift"] = d
                r["work"] += 0.5 * (v + r["v"]) * (e - r["e"])
                r["e"], r["v"] = e, v

    def hysteretic_energy(self, s, j):
        """E_h = W - 1/2 alpha k e^2 - 1/2 (1 - alpha) k Z^2 with Z = (V - alpha k e)/((1 - alpha) k)
        (the program's E_h in OpenSees' variables; docs/model.md 2.6b), or None (elastic)."""
        bw = self.m["structures"][s].get("bouc_wen")
        if not bw:
            return None
        b, r = bw[j], self.storeys[s][j]
        a, k = b["alpha"], b["ko"]
        z = (r["v"] - a * k * r["e"]) / ((1.0 - a) * k)
        return r["work"] - 0.5 * a * k * r["e"] ** 2 - 0.5 * (1.0 - a) * k * z * z

    def run(self):
        ops = self.ops
        self.build()
        self.analysis()
        self.damping()  # after the analysis: eigen and modalDamping act on it
        self.storeys = [[{"peak_drift": 0.0, "peak_force": 0.0, "residual_drift": 0.0,
                          "work": 0.0, "e": 0.0, "v": 0.0} for _ in links]
                        for links in self.links]
        self.peaks = [[0.0] * len(tr) for tr in self.track]
        self.levels = [{"peak_w": [0.0, 0.0], "max_closing": -math.inf, "peak_force": 0.0,
                        "max_penetration": 0.0, "impacts": 0, "contact_time": 0.0, "open": False}
                       for _ in self.m["levels"]]
        self.last_t = 0.0
        steps = int(round(self.duration / self.dt))
        fallbacks = 0
        start = time.perf_counter()
        for k in range(steps):
            h = (k + 1) * self.dt - ops.getTime()
            fallbacks += self.try_step(h)
            self.observe()
        seconds = time.perf_counter() - start
        return {"seconds": seconds, "steps": steps, "fallbacks": fallbacks}


def run_cases(model_class, description):
    """Parse the command line, run the case with contact and the one without on
    `model_class` (the pair's Model or a row's), and return the arguments, the result so far
    and the models run."""
    p = argparse.ArgumentParser(description=description)
    p.add_argument("--json", help="also write the results to this file")
    p.add_argument("--only", choices=["contact", "free"], default=MODEL.get("only"),
                   help="run only the case with contact or only the one without")
    p.add_argument("--dt", type=float, default=MODEL["dt"], help="analysis step, s")
    p.add_argument("--duration", type=float, default=MODEL["duration"], help="simulated time, s")
    p.add_argument("--log", default=os.devnull,
                   help="OpenSees' own messages go here (default: discarded)")
    a = p.parse_args()
    ops = import_opensees()
    ops.logFile(a.log, "-noEcho")
    result = {"title": MODEL["title"], "opensees": ops.version(), "dt": a.dt,
              "duration": a.duration, "elements": [st.get("elements", len(st["node_heights"]) - 1)
                                                   for st in MODEL["structures"]],
              "runs": {}}
    records = {}
    for case in ("contact", "free"):
        if a.only is not None and a.only != case:
            continue
        mdl = model_class(ops, MODEL, a.dt, a.duration, case == "contact")
        try:
            result["runs"][case] = mdl.run()
        except StepFailed as e:
            print(json.dumps({"error": str(e), "case": case}), file=sys.stderr)
            sys.exit(3)
        records[case] = mdl
    return a, result, records


def main():
    a, result, records = run_cases(
        Model, "OpenSeesPy model of a pounding scenario (written by `pounding export opensees`)")
    c, f = records.get("contact"), records.get("free")
    main_level = max(range(len(MODEL["levels"])), key=lambda j: MODEL["levels"][j]["height"])

    def pct(a_, b_):
        return None if a_ is None or b_ is None or b_ == 0 else 100.0 * (a_ - b_) / b_

    structures = []
    for s, st in enumerate(MODEL["structures"]):
        pw = c.levels[main_level]["peak_w"][s] if c else None
        pf = f.levels[main_level]["peak_w"][s] if f else None
        heights = []
        for i, (h, _) in enumerate((c or f).track[s]):
            heights.append({"height": h,
                           "peak_displacement": c.peaks[s][i] if c else None,
                           "peak_displacement_no_contact": f.peaks[s][i] if f else None})
        storeys = []
        for j in range(len((c or f).links[s])):
            a_ = c.storeys[s][j] if c else None
            b_ = f.storeys[s][j] if f else None
            storeys.append({
                "peak_drift": a_["peak_drift"] if a_ else None,
                "peak_drift_no_contact": b_["peak_drift"] if b_ else None,
                "peak_force": a_["peak_force"] if a_ else None,
                "peak_force_no_contact": b_["peak_force"] if b_ else None,
                "residual_drift": a_["residual_drift"] if a_ else None,
                "residual_drift_no_contact": b_["residual_drift"] if b_ else None,
                "hysteretic_energy": c.hysteretic_energy(s, j) if c else None,
                "hysteretic_energy_no_contact": f.hysteretic_energy(s, j) if f else None})
        structures.append({"name": st["name"], "peak_displacement": pw,
                           "peak_displacement_no_contact": pf, "change_percent": pct(pw, pf),
                           "heights": heights, "storeys": storeys,
                           "fe_periods": (c or f).fe_periods[s][:20]})
    levels = []
    for j, lv in enumerate(MODEL["levels"]):
        a_, b_ = (c.levels[j] if c else None), (f.levels[j] if f else None)
        levels.append({"height": lv["height"], "gap": lv["gap"],
                       "peak_force": a_["peak_force"] if a_ else None,
                       "max_penetration": a_["max_penetration"] if a_ else None,
                       "impacts": a_["impacts"] if a_ else None,
                       "contact_time": a_["contact_time"] if a_ else None,
                       "peak_displacement": a_["peak_w"] if a_ else None,
                       "peak_displacement_no_contact": b_["peak_w"] if b_ else None,
                       "required_gap": max(b_["max_closing"], 0.0) if b_ else None})
    result["structures"] = structures
    result["levels"] = levels
    if c:
        result["contact"] = {"peak_force": max(l["peak_force"] for l in levels),
                             "max_penetration": max(l["max_penetration"] for l in levels),
                             "impacts": sum(l["impacts"] for l in levels),
                             "contact_time": sum(l["contact_time"] for l in levels)}
    result["separation"] = {"time_history": levels[main_level]["required_gap"]}
    text = json.dumps(result, indent=2)
    if a.json:
        with open(a.json, "w") as fh:
            fh.write(text + "\n")
    print(text)


if __name__ == "__main__":
    main()
