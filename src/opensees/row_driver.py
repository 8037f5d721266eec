
# ---------------------------------------------------------------------------------------------
# The row's driver (a row of N buildings): the pair's Model above, generalised to N structures
# and every adjacent pair's contact levels. MODEL["levels"] holds every pair's levels, pair by
# pair, each with its "pair" (the left structure's index, 0-based: it joins structures pair and
# pair + 1); MODEL["pairs"] names each pair. Prints the headline numbers of a row's
# summary.json: per structure, and per pair (`pairs`, in row order).
# ---------------------------------------------------------------------------------------------


class RowModel(Model):
    def __init__(self, ops, model, dt, duration, contact):
        super().__init__(ops, model, dt, duration, contact)
        n = len(model["structures"])
        self.fe_periods = [[] for _ in range(n)]
        self.links = [[] for _ in range(n)]

    def build(self):
        """The structures, their Rayleigh regions and the ground loads as the pair's Model
        builds them (without its contact elements, which would join structures 1 and 2), then
        a zeroLength element at every level of every pair, between that pair's two nodes."""
        contact, self.contact = self.contact, False
        super().build()
        self.contact = contact
        ops = self.ops
        self.level_nodes = []
        for lv in self.m["levels"]:
            pair = []
            for s in (lv["pair"], lv["pair"] + 1):
                hs = self.heights[s]
                k = min(range(len(hs)), key=lambda i: abs(hs[i] - lv["height"]))
                pair.append(node_tag(s, k))
            self.level_nodes.append(pair)
        self.contact_eles = []
        if self.contact:
            # tags above any structure's (elements count from 1, storey materials from 1001)
            for j, lv in enumerate(self.m["levels"]):
                self.material(5000000 + j, lv)
                # deformation = u(right) - u(left): compression is the two approaching
                ops.element("zeroLength", 9000000 + j, self.level_nodes[j][0],
                            self.level_nodes[j][1], "-mat", 5000000 + j, "-dir", 1)
                self.contact_eles.append(9000000 + j)

    def damping(self):
        """Modal damping as the pair's: every FE mode assigned to the structure it moves most
        (the first on a tie) and given that structure's ratio for its mode number."""
        ops, m = self.ops, self.m
        modal = [st["damping"] for st in m["structures"]]
        if not any(d["kind"] == "modal" for d in modal):
            return
        n = len(modal)
        ndof = sum(len(nodes) * (2 if st["kind"] == "cantilever" else 1)
                   for nodes, st in zip(self.struct_nodes, m["structures"]))
        lam = ops.eigen("-fullGenLapack", ndof)
        count = [0] * n
        ratios = []
        for i in range(len(lam)):
            share = [sum(sum(v * v for v in ops.nodeEigenvector(node, i + 1))
                         for node in self.struct_nodes[s]) for s in range(n)]
            s = max(range(n), key=lambda q: share[q])
            d = modal[s]
            if d["kind"] == "modal":
                r = d["ratios"]
                ratios.append(r[min(count[s], len(r) - 1)])
            else:
                ratios.append(0.0)  # that structure is damped by Rayleigh
            count[s] += 1
            self.fe_periods[s].append(2.0 * math.pi / math.sqrt(lam[i]))
        ops.modalDampingQ(*ratios)

    def observe(self):
        # the pair's observation covers the storeys, every level and structures 1 and 2
        super().observe()
        ops = self.ops
        for s in range(2, len(self.track)):
            for i, (_, node) in enumerate(self.track[s]):
                x = abs(ops.nodeDisp(node, 1))
                if x > self.peaks[s][i]:
                    self.peaks[s][i] = x


def row_main():
    a, result, records = run_cases(RowModel, "OpenSeesPy model of a row of buildings (written by `pounding export opensees`)")
    c, f = records.get("contact"), records.get("free")
    lvs = MODEL["levels"]

    def pct(a_, b_):
        return None if a_ is None or b_ is None or b_ == 0 else 100.0 * (a_ - b_) / b_

    def highest(js):
        """The highest of the levels js (the first on a tie), or None."""
        best = None
        for j in js:
            if best is None or lvs[j]["height"] > lvs[best]["height"]:
                best = j
        return best

    structures = []
    for s, st in enumerate(MODEL["structures"]):
        # the headline height: the structure's highest contact level with either neighbour
        main = highest([j for j, lv in enumerate(lvs) if lv["pair"] in (s - 1, s)])
        side = 0 if main is not None and lvs[main]["pair"] == s else 1
        pw = c.levels[main]["peak_w"][side] if c and main is not None else None
        pf = f.levels[main]["peak_w"][side] if f and main is not None else None
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
    pairs = []
    for pr in MODEL["pairs"]:
        js = [j for j, lv in enumerate(lvs) if lv["pair"] == pr["index"]]
        levels = []
        for j in js:
            lv = lvs[j]
            a_, b_ = (c.levels[j] if c else None), (f.levels[j] if f else None)
            levels.append({"height": lv["height"], "gap": lv["gap"],
                           "peak_force": a_["peak_force"] if a_ else None,
                           "max_penetration": a_["max_penetration"] if a_ else None,
                           "impacts": a_["impacts"] if a_ else None,
                           "contact_time": a_["contact_time"] if a_ else None,
                           "peak_displacement": a_["peak_w"] if a_ else None,
                           "peak_displacement_no_contact": b_["peak_w"] if b_ else None,
                           "required_gap": max(b_["max_closing"], 0.0) if b_ else None})
        entry = {"index": pr["index"], "between": pr["between"], "law": pr["law"],
                 "levels": levels, "contact": None,
                 "separation": {"time_history": levels[js.index(highest(js))]["required_gap"]}}
        if c:
            entry["contact"] = {"peak_force": max(l["peak_force"] for l in levels),
                                "max_penetration": max(l["max_penetration"] for l in levels),
                                "impacts": sum(l["impacts"] for l in levels),
                                "contact_time": sum(l["contact_time"] for l in levels)}
        pairs.append(entry)
    result["structures"] = structures
    result["pairs"] = pairs
    text = json.dumps(result, indent=2)
    if a.json:
        with open(a.json, "w") as fh:
            fh.write(text + "\n")
    print(text)


if __name__ == "__main__":
    row_main()
