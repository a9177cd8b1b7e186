#!/usr/bin/env python3
"""Writes the feature programs in cases/: small ISO 14649-10/-11 files in the style of NIST's
nist_toolkit_ex1.stp, one per feature kind, operation, strategy and approach the generator
handles (and the wrong-tool cases). Run it after changing a case here; then regenerate the
golden traces with NCPOST_UPDATE_GOLDEN=1 and review the diff."""

import os

HERE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "cases")


class P21:
    def __init__(self, name, description):
        self.name, self.description = name, description
        self.lines, self.next = [], 100
        self.cache = {}

    def add(self, text):
        i = self.next
        self.next += 1
        self.lines.append(f"#{i}={text};")
        return f"#{i}"

    def once(self, key, text):
        if key not in self.cache:
            self.cache[key] = self.add(text)
        return self.cache[key]

    # ---- geometry ----
    def point(self, x, y, z):
        return self.add(f"CARTESIAN_POINT('',({x:.3f},{y:.3f},{z:.3f}))")

    def direction(self, x, y, z):
        return self.once(("d", x, y, z), f"DIRECTION('',({x:.3f},{y:.3f},{z:.3f}))")

    def placement(self, x=0, y=0, z=0, axis=(0, 0, 1), ref=(1, 0, 0)):
        return self.add(f"AXIS2_PLACEMENT_3D('',{self.point(x, y, z)},"
                        f"{self.direction(*axis)},{self.direction(*ref)})")

    def length(self, value, tol=0.1):
        t = self.once(("tol", tol), f"PLUS_MINUS_VALUE({tol},{tol},3)")
        return self.add(f"TOLERANCED_LENGTH_MEASURE({value:.3f},{t})")

    def plane(self, name, z):
        return self.add(f"PLANE('{name}',{self.placement(0, 0, z)})")

    # ---- resources ----
    def tool(self, name, body, diameter, edge_length="$", tip="$", edge_radius="$",
             hand=".RIGHT.", assembly=80.0):
        def v(x):
            return x if isinstance(x, str) else f"{x:.3f}"
        dim = self.add(f"MILLING_TOOL_DIMENSION({diameter:.3f},{v(tip)},$,{v(edge_length)},"
                       f"{v(edge_radius)},$,$)")
        # Attributes of the body's own entity after the common ones.
        extra = {"BORING_TOOL": ",.F.",  # retract_movement_forbidden
                 "COUNTERSINK": ",$", "TAPERED_ENDMILL": ",$", "WOODRUFF_KEYSEAT_MILL": ",$",
                 "T_SLOT_MILL": ",$", "SIDE_MILL": ",$", "DOVETAIL_MILL": ",$"}.get(body, "")
        b = self.add(f"{body}({dim},2,{hand},.F.,${extra})")
        comp = self.add(f"CUTTING_COMPONENT({assembly:.3f},$,$,$,$)")
        return self.add(f"MILLING_CUTTING_TOOL('{name}',{b},({comp}),{assembly:.3f},$,$)")

    def tech(self, feed, spindle):
        return self.add(f"MILLING_TECHNOLOGY({feed},.TCP.,$,{spindle},$,.F.,.F.,.F.,$)")

    def functions(self):
        return self.once("mf", "MILLING_MACHINE_FUNCTIONS(.T.,$,$,.F.,$,(),.T.,$,$,())")

    def write(self, steps):
        """steps: list of (workingstep name, feature, operation)."""
        self.secplane = getattr(self, "secplane", None)
        out = ["ISO-10303-21;", "HEADER;",
               f"FILE_DESCRIPTION(('ncpost feature case: {self.description}'),'2;1');",
               f"FILE_NAME('{self.name}.stp','2026-11-22T00:00:00',('ncpost'),('ncpost project'),"
               "'','hand written','');",
               "FILE_SCHEMA(('MACHINING_SCHEMA','MILLING_SCHEMA'));", "ENDSEC;", "DATA;"]
        ws_ids = [f"#{10 + k}" for k in range(len(steps))]
        out.append(f"#1=PROJECT('{self.name.upper()}',#2,(#4),$,$,$);")
        out.append(f"#2=WORKPLAN('MAIN',({','.join(ws_ids)}),$,#8,$);")
        out.append("#4=WORKPIECE('BLOCK',$,0.01,$,$,$,());")
        out.append(f"#8=SETUP('SETUP',{self.setup_origin},{self.secplane},(#9));")
        out.append(f"#9=WORKPIECE_SETUP(#4,{self.workpiece_origin},$,$,());")
        for wid, (name, feature, operation) in zip(ws_ids, steps):
            out.append(f"{wid}=MACHINING_WORKINGSTEP('{name}',{self.secplane},{feature},"
                       f"{operation},$);")
        out += self.lines
        out += ["ENDSEC;", "END-ISO-10303-21;", ""]
        with open(os.path.join(HERE, self.name + ".stp"), "w") as f:
            f.write("\n".join(out))


def program(name, description):
    p = P21(name, description)
    p.secplane = p.plane("SECURITY PLANE", 50)
    p.setup_origin = p.placement()
    p.workpiece_origin = p.placement()
    return p


def mill(p, d=10.0, edge=30.0, radius="$"):
    return p.tool(f"ENDMILL {d:g}", "ENDMILL", d, edge_length=edge, edge_radius=radius)


def face(p, x, y, z, travel, width, depth, direction=(0, 1, 0), ops="()"):
    path = p.add(f"LINEAR_PATH($,{p.length(travel)},{p.direction(*direction)})")
    param = p.add(f"NUMERIC_PARAMETER('WIDTH',{width:.3f},'MM')")
    prof = p.add(f"LINEAR_PROFILE($,{param})")
    return p.add(f"PLANAR_FACE('FACE',#4,{ops},{p.placement(x, y, z)},"
                 f"{p.plane('FACE DEPTH', -depth)},{path},{prof},$,())")


def rect_pocket(p, x, y, length, width, depth, corner, ref=(1, 0, 0), floor="$",
                bottom="PLANAR_POCKET_BOTTOM_CONDITION()"):
    prof = p.add(f"RECTANGULAR_CLOSED_PROFILE($,{p.length(width)},{p.length(length)})")
    b = p.add(bottom)
    c = p.length(corner) if corner is not None else "$"
    return p.add(f"CLOSED_POCKET('POCKET',#4,(),{p.placement(x, y, 0, ref=ref)},"
                 f"{p.plane('POCKET DEPTH', -depth)},(),$,{b},{floor},{c},{prof})")


def circ_pocket(p, x, y, diameter, depth):
    prof = p.add(f"CIRCULAR_CLOSED_PROFILE($,{p.length(diameter)})")
    b = p.add("PLANAR_POCKET_BOTTOM_CONDITION()")
    return p.add(f"CLOSED_POCKET('ROUND POCKET',#4,(),{p.placement(x, y, 0)},"
                 f"{p.plane('POCKET DEPTH', -depth)},(),$,{b},$,$,{prof})")


def hole(p, x, y, diameter, depth, bottom="THROUGH_BOTTOM_CONDITION()"):
    b = p.add(bottom)
    return p.add(f"ROUND_HOLE('HOLE D{diameter:g}',#4,(),{p.placement(x, y, 0)},"
                 f"{p.plane('HOLE DEPTH', -depth)},{p.length(diameter, 0.02)},$,{b})")


def bs(p, kind, name, tool, tech, strategy, axial, radial, side, bottom, approach="$",
       retract_plane=5.0, retract="$"):
    def v(x):
        return "$" if x is None else f"{x:.3f}" if x >= 0.001 else f"{x:.3E}"
    return p.add(f"BOTTOM_AND_SIDE_{kind}_MILLING($,$,'{name}',{retract_plane:.3f},$,{tool},{tech},"
                 f"{p.functions()},$,{approach},{retract},{strategy},{v(axial)},{v(radial)},{v(side)},"
                 f"{v(bottom)})")


def side_op(p, kind, name, tool, tech, strategy, axial, allowance, approach="$"):
    return p.add(f"SIDE_{kind}_MILLING($,$,'{name}',5.000,$,{tool},{tech},{p.functions()},$,"
                 f"{approach},$,{strategy},{axial:.3f},$,{allowance:.3f})")


def slot_feature(p, name, x, y, path, profile, ends, depth):
    return p.add(f"SLOT('{name}',#4,(),{p.placement(x, y, 0)},{p.plane('SLOT DEPTH', -depth)},"
                 f"{path},{profile},({','.join(ends)}))")


def line_path(p, length, direction=(1, 0, 0)):
    return p.add(f"LINEAR_PATH($,{p.length(length)},{p.direction(*direction)})")


def vee_profile(p, angle, radius=0.0, tilt=None):
    tilt = 90 - angle / 2 if tilt is None else tilt
    return p.add(f"VEE_PROFILE($,{p.length(radius)},{angle:.3f},{tilt:.3f})")


def step_feature(p, name, x, y, length, direction, foot, depth, angle=90.0, radius=0.0, tilt=0.0):
    """A step whose open boundary starts at (x, y) along `direction`; `foot` is the foot of its
    wall (the vee's vertex) in the feature's coordinates, or None for a step without a wall."""
    path = line_path(p, length, direction)
    if foot is None:
        wall = "$"
    else:
        wall = p.add(f"VEE_PROFILE({p.placement(*foot)},{p.length(radius, 0.05)},{angle:.3f},"
                     f"{tilt:.3f})")
    return p.add(f"STEP('{name}',#4,(),{p.placement(x, y, 0)},{p.plane('STEP DEPTH', -depth)},"
                 f"{path},{wall},())")


def thread_feature(p, name, x, y, hole_feature, major, threads, unit, hand, depth):
    count = p.add(f"NUMERIC_PARAMETER('THREADS',{threads:.6f},'{unit}')")
    hand = p.add(f"DESCRIPTIVE_PARAMETER('HAND','{hand}')")
    fit = p.add("DESCRIPTIVE_PARAMETER('FIT','6H')")
    form = p.add("DESCRIPTIVE_PARAMETER('FORM','ISO METRIC')")
    area = p.add(f"PARTIAL_AREA_DEFINITION({depth:.3f},{p.placement(0, 0, 0)},$)")
    return p.add(f"DEFINED_THREAD('{name}',#4,(),{p.placement(x, y, 0)},"
                 f"{p.plane('THREAD DEPTH', -depth)},{area},({hole_feature}),.T.,$,{fit},{form},"
                 f"{major:.3f},{count},{hand},{major - 0.6495 * 25.4 / 13:.3f},$,$)")


def plane_op(p, kind, name, tool, tech, strategy, axial, bottom=None, approach="$"):
    v = "$" if bottom is None else f"{bottom:.3f}"
    return p.add(f"PLANE_{kind}_MILLING($,$,'{name}',5.000,$,{tool},{tech},{p.functions()},$,"
                 f"{approach},$,{strategy},{axial:.3f},{v})")


def drill_op(p, entity, name, tool, tech, extra="", cutting_depth="$", dwell="$", strategy="$",
             retract_ratio="$"):
    return p.add(f"{entity}($,$,'{name}',3.000,$,{tool},{tech},{p.functions()},$,{cutting_depth},"
                 f"$,{dwell},{retract_ratio},{strategy}{extra})")


def main():
    os.makedirs(HERE, exist_ok=True)

    # ---- planar faces ----
    p = program("face-unidirectional", "planar face, plane rough milling, unidirectional, two levels")
    t, tech = mill(p, 20, 25), p.tech(0.05, -20.0)
    f = face(p, 0, 0, 3, 80, 50, 3)
    s = p.add(f"UNIDIRECTIONAL_MILLING(0.2,.T.,{p.direction(1, 0, 0)},.CLIMB.)")
    p.write([("FACE UNIDIRECTIONAL", f, plane_op(p, "ROUGH", "FACE ROUGH", t, tech, s, 2.0, 0.5))])

    p = program("face-bidirectional-right", "planar face, plane finish milling, bidirectional to the right across the travel, ramp named")
    t, tech = mill(p, 16, 25), p.tech(0.04, -25.0)
    f = face(p, 10, 20, 0, 60, 40, 1)
    s = p.add(f"BIDIRECTIONAL_MILLING(0.1,.T.,{p.direction(1, 0, 0)},.RIGHT.,.STRAIGHTLINE.)")
    ramp = p.add("PLUNGE_RAMP($,5.0)")
    p.write([("FACE BIDIRECTIONAL", f, plane_op(p, "FINISH", "FACE FINISH", t, tech, s, 1.0, None, ramp))])

    # ---- closed pockets ----
    p = program("pocket-rect-helix", "rectangular pocket, rough + finish, contour parallel climb, helix")
    t, tech = mill(p, 10, 20), p.tech(0.03, -40.0)
    f = rect_pocket(p, 50, 40, 60, 40, 12, 6)
    s1 = p.add("CONTOUR_PARALLEL(0.4,.T.,$,.CLIMB.)")
    s2 = p.add("CONTOUR_PARALLEL(0.4,.T.,.CCW.,$)")
    hx = p.add("PLUNGE_HELIX($,3.0,5.0)")
    p.write([("POCKET ROUGH", f, bs(p, "ROUGH", "ROUGH", t, tech, s1, 5.0, None, 0.5, 0.3, hx)),
             ("POCKET FINISH", f, bs(p, "FINISH", "FINISH", t, tech, s2, 12.0, None, None, None))])

    p = program("pocket-circle-ramp", "circular pocket, ramp entry, conventional")
    t, tech = mill(p, 12, 20), p.tech(0.03, -35.0)
    f = circ_pocket(p, 0, 0, 50, 8)
    s = p.add("CONTOUR_PARALLEL($,.T.,$,.CONVENTIONAL.)")
    ramp = p.add("PLUNGE_RAMP($,3.0)")
    p.write([("ROUND POCKET", f, bs(p, "ROUGH", "ROUGH", t, tech, s, 4.0, 5.0, 0.0, 0.0, ramp))])

    p = program("pocket-rect-zigzag", "rotated rectangular pocket, zigzag entry, rotation cw")
    t, tech = mill(p, 8, 20), p.tech(0.03, -40.0)
    f = rect_pocket(p, 30, 30, 40, 24, 6, 5, ref=(0.0, 1.0, 0.0))
    s = p.add("CONTOUR_PARALLEL(0.3,.T.,.CW.,$)")
    zz = p.add("PLUNGE_ZIGZAG($,4.0,10.0)")
    p.write([("POCKET ZIGZAG", f, bs(p, "ROUGH", "ROUGH", t, tech, s, 3.0, None, 0.2, 0.2, zz))])

    p = program("pocket-toolaxis-fillet", "pocket with a floor radius, bull nose tool, axial plunge, single pass")
    t = p.tool("BULLNOSE 10 R1", "BULLNOSE_ENDMILL", 10, edge_length=20.0, edge_radius=1.0)
    tech = p.tech(0.02, -40.0)
    f = rect_pocket(p, 0, 0, 30, 30, 4, 5, floor=p.length(1.0, 0.05))
    s = p.add("CONTOUR_PARALLEL(0.5,.F.,.CCW.,$)")
    ax = p.add("PLUNGE_TOOLAXIS($)")
    p.write([("POCKET PLUNGE", f, bs(p, "FINISH", "FINISH", t, tech, s, None, None, None, None, ax))])

    p = program("pocket-side-finish", "circular and rectangular pockets roughed with a side allowance, then side finish milling of the walls")
    t, tech = mill(p, 10, 20), p.tech(0.03, -40.0)
    rect = rect_pocket(p, 0, 0, 40, 30, 6, 6)
    circle = circ_pocket(p, 60, 0, 30, 6)
    cp = p.add("CONTOUR_PARALLEL(0.5,.T.,$,.CLIMB.)")

    def side(name, strategy, axial, allowance):
        return p.add(f"SIDE_FINISH_MILLING($,$,'{name}',5.000,$,{t},{tech},{p.functions()},$,$,$,"
                     f"{strategy},{axial:.3f},$,{allowance:.3f})")
    p.write([("RECT ROUGH", rect, bs(p, "ROUGH", "ROUGH 1", t, tech, cp, 3.0, None, 1.0, 0.0)),
             ("RECT WALLS", rect, side("SIDE 1", cp, 6.0, 0.0)),
             ("CIRCLE ROUGH", circle, bs(p, "ROUGH", "ROUGH 2", t, tech, cp, 3.0, None, 1.0, 0.0)),
             ("CIRCLE WALLS", circle, side("SIDE 2", "$", 3.0, 0.0))])

    p = program("outside-profile", "general outside profiles (rectangle, circle): side rough then finish, climb and conventional")
    t, tech = mill(p, 12, 25), p.tech(0.03, -40.0)

    def gop(name, x, y, boundary, depth):
        path = p.add(f"LINEAR_PATH($,{p.length(depth)},{p.direction(0, 0, -1)})")
        return p.add(f"GENERAL_OUTSIDE_PROFILE('{name}',#4,(),{p.placement(x, y, 0)},"
                     f"{p.plane('PROFILE DEPTH', -depth)},{path},{boundary})")
    box = gop("BOX", 0, 0, p.add(f"RECTANGULAR_CLOSED_PROFILE($,{p.length(40)},{p.length(60)})"), 8)
    boss = gop("ROUND", 100, 0, p.add(f"CIRCULAR_CLOSED_PROFILE($,{p.length(30)})"), 5)
    climb = p.add("CONTOUR_PARALLEL($,.T.,$,.CLIMB.)")
    conv = p.add("CONTOUR_PARALLEL($,.T.,$,.CONVENTIONAL.)")

    def side(kind, name, strategy, axial, allowance):
        return p.add(f"SIDE_{kind}_MILLING($,$,'{name}',5.000,$,{t},{tech},{p.functions()},$,$,$,"
                     f"{strategy},{axial:.3f},$,{allowance:.3f})")
    p.write([("BOX ROUGH", box, side("ROUGH", "BOX R", climb, 4.0, 0.5)),
             ("BOX FINISH", box, side("FINISH", "BOX F", climb, 8.0, 0.0)),
             ("ROUND FINISH", boss, side("FINISH", "ROUND F", conv, 2.5, 0.0))])

    p = program("pocket-raster", "pockets with bidirectional, unidirectional, bidirectional-contour and contour-bidirectional")
    t, tech = mill(p, 10, 20), p.tech(0.03, -40.0)
    rect = rect_pocket(p, 0, 0, 50, 30, 4, 8)
    circle = circ_pocket(p, 80, 0, 40, 3)
    bi = p.add(f"BIDIRECTIONAL_MILLING(0.2,.T.,{p.direction(1, 0, 0)},.LEFT.,$)")
    uni = p.add(f"UNIDIRECTIONAL_MILLING(0.2,.T.,{p.direction(0, 1, 0)},.CLIMB.)")
    bc = p.add(f"BIDIRECTIONAL_CONTOUR(0.2,.T.,{p.direction(1, 0, 0)},.RIGHT.,.CCW.,$)")
    cb = p.add(f"CONTOUR_BIDIRECTIONAL(0.2,.T.,{p.direction(0, 1, 0)},$,.CW.,$)")
    p.write([("RECT BIDIRECTIONAL", rect, bs(p, "ROUGH", "BI", t, tech, bi, 4.0, None, 0.5, 0.2)),
             ("RECT UNIDIRECTIONAL", rect, bs(p, "FINISH", "UNI", t, tech, uni, 4.0, None, None, None)),
             ("CIRCLE BIDIRECTIONAL CONTOUR", circle, bs(p, "ROUGH", "BC", t, tech, bc, 3.0, None, 0.3, 0.0)),
             ("CIRCLE CONTOUR BIDIRECTIONAL", circle, bs(p, "FINISH", "CB", t, tech, cb, 3.0, None, None, None))])

    # ---- slots ----
    p = program("slots", "straight slots: radiused, flat and open ends, square-U and rounded-U, center milling")
    mill10, tech = mill(p, 10, 20), p.tech(0.03, -40.0)
    ball8 = p.tool("BALL 8", "BALL_ENDMILL", 8, edge_length=16.0, edge_radius=4.0)

    def slot(name, x, y, length, direction, profile, ends, depth):
        path = p.add(f"LINEAR_PATH($,{p.length(length)},{p.direction(*direction)})")
        return p.add(f"SLOT('{name}',#4,(),{p.placement(x, y, 0)},{p.plane('SLOT DEPTH', -depth)},"
                     f"{path},{profile},({','.join(ends)}))")
    square = p.add(f"SQUARE_U_PROFILE($,{p.length(16)},{p.length(0)},90.0,{p.length(0)},90.0)")
    rounded = p.add(f"ROUNDED_U_PROFILE($,{p.length(8)})")
    radiused = p.add("RADIUSED_SLOT_END_TYPE()")
    flat = p.add(f"FLAT_SLOT_END_TYPE({p.length(6)},{p.length(6)})")
    opened = p.add("OPEN_SLOT_END_TYPE()")
    s1 = slot("SLOT RADIUSED", 0, 0, 40, (1, 0, 0), square, [radiused, radiused], 6)
    s2 = slot("SLOT FLAT", 0, 40, 30, (0, 1, 0), square, [flat, flat], 5)
    s3 = slot("SLOT OPEN", -20, 100, 50, (1, 0, 0), square, [opened, opened], 4)
    s4 = slot("SLOT ROUND", 0, 150, 30, (0.6, 0.8, 0), rounded, [radiused], 4)
    cp = p.add("CONTOUR_PARALLEL(0.5,.T.,.CCW.,$)")
    centre = p.add("CENTER_MILLING($,.T.)")
    ramp = p.add("PLUNGE_RAMP($,10.0)")
    p.write([("SLOT RADIUSED ENDS", s1, bs(p, "ROUGH", "SLOT 1", mill10, tech, cp, 3.0, None, 0.0, 0.0, ramp)),
             ("SLOT FLAT ENDS", s2, bs(p, "ROUGH", "SLOT 2", mill10, tech, cp, 5.0, None, 0.0, 0.0)),
             ("SLOT OPEN ENDS", s3, bs(p, "FINISH", "SLOT 3", mill10, tech, cp, 2.0, None, None, None)),
             ("SLOT CENTRE", s4, bs(p, "FINISH", "SLOT 4", ball8, tech, centre, 2.0, None, None, None, ramp))])


    # ---- slots: profiles, end types and paths made by form tools ----
    p = program("slot-vee", "vee slots: a 90-degree countersink along the centre (radiused ends, two levels), a 60-degree pointed cutter with a tip radius (open ends)")
    sink = p.tool("COUNTERSINK 16 X 90", "COUNTERSINK", 16, edge_length=12.0, tip=45.0)
    engraver = p.tool("ENGRAVER 10 X 60 R1", "ENDMILL", 10, edge_length=15.0, tip=60.0, edge_radius=1.0)
    tech = p.tech(0.02, -40.0)
    radiused, opened = p.add("RADIUSED_SLOT_END_TYPE()"), p.add("OPEN_SLOT_END_TYPE()")
    v90 = slot_feature(p, "VEE 90", 0, 0, line_path(p, 40), vee_profile(p, 90), [radiused, radiused], 5)
    v60 = slot_feature(p, "VEE 60 R1", 0, 30, line_path(p, 50, (0.6, 0.8, 0)), vee_profile(p, 60, 1.0, 60.0),
                       [opened, opened], 6)
    centre = p.add("CENTER_MILLING($,.T.)")
    ramp = p.add("PLUNGE_RAMP($,10.0)")
    p.write([("VEE 90 RADIUSED", v90, bs(p, "FINISH", "VEE 1", sink, tech, centre, 2.5, None, None, None, ramp)),
             ("VEE 60 OPEN", v60, bs(p, "FINISH", "VEE 2", engraver, tech, centre, None, None, None, None))])

    p = program("slot-partial-circular", "partial-circular slots: a ball of the profile radius along the centre, and a smaller ball stepped across it (rings about radiused ends, lines out of open ends)")
    ball12 = p.tool("BALL 12", "BALL_ENDMILL", 12, edge_length=20.0, edge_radius=6.0)
    ball6 = p.tool("BALL 6", "BALL_ENDMILL", 6, edge_length=15.0, edge_radius=3.0)
    tech = p.tech(0.02, -50.0)
    radiused, opened = p.add("RADIUSED_SLOT_END_TYPE()"), p.add("OPEN_SLOT_END_TYPE()")
    arc120 = p.add(f"PARTIAL_CIRCULAR_PROFILE($,{p.length(6)},120.0)")
    s1 = slot_feature(p, "ROUND 12 FULL", 0, 0, line_path(p, 40), arc120, [radiused, radiused], 3)
    s2 = slot_feature(p, "ROUND 12 STEPPED", 0, 30, line_path(p, 40), arc120, [radiused, opened], 3)
    s3 = slot_feature(p, "ROUND 12 OPEN", 0, 60, line_path(p, 30, (0, 1, 0)), arc120, [opened, opened], 3)
    cp = p.add("CONTOUR_PARALLEL($,.T.,$,.CLIMB.)")
    p.write([("ROUND FULL", s1, bs(p, "FINISH", "ROUND 1", ball12, tech, cp, None, None, None, None)),
             ("ROUND STEPPED", s2, bs(p, "FINISH", "ROUND 2", ball6, tech, cp, 1.5, None, None, None)),
             ("ROUND STEPPED OPEN", s3, bs(p, "FINISH", "ROUND 3", ball6, tech, "$", None, None, None, None))])

    p = program("slot-ends-mixed", "square-U slots with mixed ends (radiused and flat, open and flat) and flat ends with two different corner radii")
    mill10, tech = mill(p, 10, 20), p.tech(0.03, -40.0)
    square = p.add(f"SQUARE_U_PROFILE($,{p.length(16)},{p.length(0)},90.0,{p.length(0)},90.0)")
    radiused, opened = p.add("RADIUSED_SLOT_END_TYPE()"), p.add("OPEN_SLOT_END_TYPE()")
    flat6 = p.add(f"FLAT_SLOT_END_TYPE({p.length(6)},{p.length(6)})")
    flat_unequal = p.add(f"FLAT_SLOT_END_TYPE({p.length(5.5)},{p.length(8)})")
    s1 = slot_feature(p, "RADIUSED AND FLAT", 0, 0, line_path(p, 40), square, [radiused, flat6], 5)
    s2 = slot_feature(p, "OPEN AND FLAT", -10, 40, line_path(p, 50), square, [opened, flat_unequal], 4)
    s3 = slot_feature(p, "FLAT 5.5 AND 8", 0, 80, line_path(p, 30, (0, 1, 0)), square, [flat_unequal, flat_unequal], 4)
    cp = p.add("CONTOUR_PARALLEL(0.5,.T.,.CCW.,$)")
    bi = p.add(f"BIDIRECTIONAL_MILLING(0.3,.T.,{p.direction(1, 0, 0)},.LEFT.,$)")
    p.write([("RADIUSED + FLAT", s1, bs(p, "ROUGH", "MIXED 1", mill10, tech, cp, 2.5, None, 0.0, 0.0)),
             ("OPEN + FLAT", s2, bs(p, "ROUGH", "MIXED 2", mill10, tech, bi, 4.0, None, 0.0, 0.0)),
             ("FLAT UNEQUAL", s3, bs(p, "FINISH", "MIXED 3", mill10, tech, cp, 2.0, None, None, None))])

    p = program("slot-woodruff", "woodruff ends: a rounded-U slot with two, a partial-circular slot with one woodruff and one radiused end, each a ball along the centre rising along the arc of the end")
    ball8 = p.tool("BALL 8", "BALL_ENDMILL", 8, edge_length=16.0, edge_radius=4.0)
    ball12 = p.tool("BALL 12", "BALL_ENDMILL", 12, edge_length=20.0, edge_radius=6.0)
    tech = p.tech(0.02, -50.0)
    rounded = p.add(f"ROUNDED_U_PROFILE($,{p.length(8)})")
    arc120 = p.add(f"PARTIAL_CIRCULAR_PROFILE($,{p.length(6)},120.0)")
    w20 = p.add(f"WOODRUFF_SLOT_END_TYPE({p.length(20)})")
    w15 = p.add(f"WOODRUFF_SLOT_END_TYPE({p.length(15)})")
    radiused = p.add("RADIUSED_SLOT_END_TYPE()")
    s1 = slot_feature(p, "KEYWAY 8", 0, 0, line_path(p, 30), rounded, [w20, w20], 5)
    s2 = slot_feature(p, "ROUND WOODRUFF", 0, 40, line_path(p, 30, (0, 1, 0)), arc120, [w15, radiused], 3)
    centre = p.add("CENTER_MILLING($,.T.)")
    p.write([("KEYWAY WOODRUFF", s1, bs(p, "FINISH", "KEY", ball8, tech, centre, 2.0, None, None, None)),
             ("ROUND WOODRUFF", s2, bs(p, "FINISH", "ROUND", ball12, tech, centre, None, None, None, None))])

    p = program("slot-circular", "slots along circles: a ring groove (loop end, helical ramp), a vee along an arc with radiused ends, a square-U along a clockwise arc cut by an end mill of its width")
    ball6 = p.tool("BALL 6", "BALL_ENDMILL", 6, edge_length=15.0, edge_radius=3.0)
    sink = p.tool("COUNTERSINK 16 X 90", "COUNTERSINK", 16, edge_length=12.0, tip=45.0)
    mill10, tech = mill(p, 10, 20), p.tech(0.02, -40.0)
    loop = p.add("LOOP_SLOT_END_TYPE()")
    radiused = p.add("RADIUSED_SLOT_END_TYPE()")
    ring = p.add(f"COMPLETE_CIRCULAR_PATH($,{p.length(30)})")
    arc = p.add(f"PARTIAL_CIRCULAR_PATH($,{p.length(25)},90.0)")
    back = p.add(f"PARTIAL_CIRCULAR_PATH($,{p.length(40)},-120.0)")
    g1 = slot_feature(p, "O-RING GROOVE", 0, 0, ring, p.add(f"ROUNDED_U_PROFILE($,{p.length(6)})"), [loop], 3)
    g2 = slot_feature(p, "VEE ARC", 100, 0, arc, vee_profile(p, 90), [radiused, radiused], 4)
    g3 = slot_feature(p, "SQUARE ARC", 0, 100, back,
                      p.add(f"SQUARE_U_PROFILE($,{p.length(10)},{p.length(0)},90.0,{p.length(0)},90.0)"),
                      [radiused, radiused], 3)
    centre = p.add("CENTER_MILLING($,.T.)")
    ramp5 = p.add("PLUNGE_RAMP($,5.0)")
    p.write([("RING GROOVE", g1, bs(p, "FINISH", "GROOVE", ball6, tech, centre, 1.5, None, None, None, ramp5, retract=ramp5)),
             ("VEE ALONG ARC", g2, bs(p, "FINISH", "VEE ARC", sink, tech, centre, None, None, None, None)),
             ("SQUARE ALONG ARC", g3, bs(p, "FINISH", "SQUARE ARC", mill10, tech, centre, 1.5, None, None, None, ramp5))])

    # ---- steps ----
    p = program("step", "steps: open boundary and a wall located by the placement of its vee; bidirectional with a bull nose making the wall radius, one-way and side finishing of a wall on the other side")
    bull = p.tool("BULLNOSE 10 R1", "BULLNOSE_ENDMILL", 10, edge_length=20.0, edge_radius=1.0)
    mill12, tech = mill(p, 12, 25), p.tech(0.03, -40.0)
    st1 = step_feature(p, "STEP R1", 0, 0, 60, (0, 1, 0), (25, 0, -8), 8, radius=1.0)
    st2 = step_feature(p, "STEP LEFT", 100, 0, 50, (1, 0, 0), (0, -18, 0), 6)
    bi = p.add(f"BIDIRECTIONAL_MILLING(0.2,.T.,{p.direction(0, 1, 0)},$,$)")
    uni = p.add(f"UNIDIRECTIONAL_MILLING(0.3,.T.,$,.CLIMB.)")
    cp = p.add("CONTOUR_PARALLEL($,.T.,$,.CLIMB.)")
    p.write([("STEP BIDIRECTIONAL", st1, bs(p, "ROUGH", "STEP 1", bull, tech, bi, 4.0, None, 0.0, 0.0)),
             ("STEP ONE WAY", st2, bs(p, "ROUGH", "STEP 2", mill12, tech, uni, 3.0, None, 0.3, 0.0)),
             ("STEP WALL", st2, side_op(p, "FINISH", "STEP 2 WALL", mill12, tech, cp, 6.0, 0.0))])

    # ---- thread drilling ----
    p = program("thread-drilling", "thread drilling: drill to depth, helix up the thread with its pitch, out along the axis; M16x2 right-hand through, 1/2-13 left-hand blind")
    bgf14 = p.tool("THREAD DRILL MILL 14", "MILLING_THREADING_TOOL", 14, edge_length=40.0, tip=31.0)
    bgf108 = p.tool("THREAD DRILL MILL 10.8", "MILLING_THREADING_TOOL", 10.8, edge_length=40.0, tip=31.0)
    h1 = hole(p, 0, 0, 14, 20)
    h2 = hole(p, 40, 0, 10.8, 20, "FLAT_HOLE_BOTTOM()")
    t1 = thread_feature(p, "M16X2", 0, 0, h1, 16, 0.5, "1/MM", "RIGHT", 20)
    t2 = thread_feature(p, "1/2-13 UNC LH", 40, 0, h2, 12.7, 13, "TPI", "LEFT", 15)

    def thread_op(name, tool, tech):
        return p.add(f"THREAD_DRILLING($,$,'{name}',3.000,$,{tool},{tech},{p.functions()},$,$,$,$,$,$,.F.)")
    p.write([("THREAD M16", t1, thread_op("BGF M16", bgf14, p.tech(0.01, -25.0))),
             ("THREAD 1/2 LH", t2, thread_op("BGF 1/2", bgf108, p.tech(0.008, -30.0)))])

    # ---- retract strategies, the approach run backwards ----
    p = program("pocket-retract", "pockets left by a helix and by a ramp (the retract strategy of the operation)")
    t, tech = mill(p, 10, 20), p.tech(0.03, -40.0)
    f1 = rect_pocket(p, 0, 0, 50, 30, 6, 6)
    f2 = circ_pocket(p, 80, 0, 40, 5)
    hx = p.add("PLUNGE_HELIX($,3.0,5.0)")
    ramp = p.add("PLUNGE_RAMP($,4.0)")
    cp = p.add("CONTOUR_PARALLEL(0.4,.T.,$,.CLIMB.)")
    # General outlines: an L pocket left by a helix about where the (default) helix came down, a
    # hexagon by a ramp along the approach's ramp line.
    ell = polyline(p, [(0, 0), (60, 0), (60, 25), (25, 25), (25, 50), (0, 50)])
    f3 = general_pocket(p, "L OUT", 0, 60, ell, 6, corner=6)
    f4 = general_pocket(p, "HEX OUT", 100, 60, None, 5, corner=6, profile=ngon(p, 50, 6, False))
    hx_any = p.add("PLUNGE_HELIX($,4.0,5.0)")
    p.write([("POCKET HELIX OUT", f1, bs(p, "ROUGH", "HELIX OUT", t, tech, cp, 3.0, None, 0.0, 0.0, hx, retract=hx)),
             ("POCKET RAMP OUT", f2, bs(p, "ROUGH", "RAMP OUT", t, tech, cp, 5.0, None, 0.0, 0.0, ramp, retract=ramp)),
             ("L HELIX OUT", f3, bs(p, "ROUGH", "L HELIX OUT", t, tech, cp, 3.0, None, 0.0, 0.0, retract=hx_any)),
             ("HEX RAMP OUT", f4, bs(p, "ROUGH", "HEX RAMP OUT", t, tech, cp, 5.0, None, 0.0, 0.0, ramp, retract=ramp))])

    p = program("retract-refused", "retracts from a general pocket that cannot be made: a ramp out after a helix in, a helix too wide")
    t, tech = mill(p, 10, 20), p.tech(0.03, -40.0)
    f3 = general_pocket(p, "L OUT", 0, 60, polyline(p, [(0, 0), (60, 0), (60, 25), (25, 25), (25, 50), (0, 50)]), 6, corner=6)
    ramp = p.add("PLUNGE_RAMP($,4.0)")
    hx_wide = p.add("PLUNGE_HELIX($,30.0,5.0)")
    cp = p.add("CONTOUR_PARALLEL(0.4,.T.,$,.CLIMB.)")
    p.write([("L RAMP OUT AFTER A HELIX", f3, bs(p, "ROUGH", "L RAMP OUT", t, tech, cp, 3.0, None, 0.0, 0.0, retract=ramp)),
             ("L HELIX OUT TOO WIDE", f3, bs(p, "ROUGH", "L WIDE OUT", t, tech, cp, 3.0, None, 0.0, 0.0, retract=hx_wide))])

    # ---- wrong tools for the new shapes: STEPNC-102 naming the tool and the feature ----
    p = program("wrong-tools-shapes", "tools that cannot make vee, partial-circular, woodruff-ended slots, steps and threads")
    tech = p.tech(0.02, -40.0)
    sink60 = p.tool("COUNTERSINK 16 X 60", "COUNTERSINK", 16, edge_length=12.0, tip=60.0)
    sink_small = p.tool("COUNTERSINK 6 X 90", "COUNTERSINK", 6, edge_length=12.0, tip=45.0)
    flat10 = mill(p, 10, 20)
    ball16 = p.tool("BALL 16", "BALL_ENDMILL", 16, edge_length=20.0, edge_radius=8.0)
    keyseat = p.tool("WOODRUFF CUTTER 25", "WOODRUFF_KEYSEAT_MILL", 25, edge_length=6.0)
    bull2 = p.tool("BULLNOSE 10 R2", "BULLNOSE_ENDMILL", 10, edge_length=20.0, edge_radius=2.0)
    drill = p.tool("DRILL 14", "TWIST_DRILL", 14, edge_length=40.0, tip=31.0)
    bgf12 = p.tool("THREAD DRILL MILL 12", "MILLING_THREADING_TOOL", 12, edge_length=40.0, tip=31.0)
    radiused = p.add("RADIUSED_SLOT_END_TYPE()")
    v90 = slot_feature(p, "VEE 90", 0, 0, line_path(p, 40), vee_profile(p, 90), [radiused, radiused], 5)
    arc120 = p.add(f"PARTIAL_CIRCULAR_PROFILE($,{p.length(6)},120.0)")
    pc = slot_feature(p, "ROUND 12", 0, 30, line_path(p, 40), arc120, [radiused, radiused], 3)
    square = p.add(f"SQUARE_U_PROFILE($,{p.length(12)},{p.length(0)},90.0,{p.length(0)},90.0)")
    w12 = p.add(f"WOODRUFF_SLOT_END_TYPE({p.length(12)})")
    key = slot_feature(p, "KEYWAY 12", 0, 60, line_path(p, 30), square, [w12, w12], 6)
    st = step_feature(p, "STEP R1", 100, 0, 60, (0, 1, 0), (25, 0, -8), 8, radius=1.0)
    w4 = p.add(f"WOODRUFF_SLOT_END_TYPE({p.length(4)})")
    shallow_key = slot_feature(p, "SHALLOW KEYWAY 12", 0, 90, line_path(p, 30),
                               p.add(f"ROUNDED_U_PROFILE($,{p.length(12)})"), [w4, w4], 3)
    ball12 = p.tool("BALL 12", "BALL_ENDMILL", 12, edge_length=20.0, edge_radius=6.0)
    h = hole(p, 100, 100, 14, 20)
    th = thread_feature(p, "M16X2", 100, 100, h, 16, 0.5, "1/MM", "RIGHT", 20)
    centre = p.add("CENTER_MILLING($,.T.)")

    def thread_op(name, tool):
        return p.add(f"THREAD_DRILLING($,$,'{name}',3.000,$,{tool},{tech},{p.functions()},$,$,$,$,$,$,.F.)")
    p.write([("VEE WRONG ANGLE", v90, bs(p, "FINISH", "VEE 60", sink60, tech, centre, None, None, None, None)),
             ("VEE FLAT END MILL", v90, bs(p, "FINISH", "VEE FLAT", flat10, tech, centre, None, None, None, None)),
             ("VEE CONE TOO NARROW", v90, bs(p, "FINISH", "VEE SMALL", sink_small, tech, centre, None, None, None, None)),
             ("ROUND NOT A BALL", pc, bs(p, "FINISH", "ROUND FLAT", flat10, tech, centre, None, None, None, None)),
             ("ROUND BALL TOO BIG", pc, bs(p, "FINISH", "ROUND 16", ball16, tech, centre, None, None, None, None)),
             ("WOODRUFF END MILL", key, bs(p, "FINISH", "KEY FLAT", flat10, tech, centre, None, None, None, None)),
             ("WOODRUFF KEYSEAT CUTTER", key, bs(p, "FINISH", "KEY CUTTER", keyseat, tech, centre, None, None, None, None)),
             ("WOODRUFF SMALLER THAN THE BALL", shallow_key, bs(p, "FINISH", "KEY 12", ball12, tech, centre, None, None, None, None)),
             ("STEP CORNER TOO BIG", st, bs(p, "FINISH", "STEP R2", bull2, tech, "$", None, None, None, None)),
             ("STEP CORNER TOO SMALL", st, bs(p, "FINISH", "STEP FLAT", flat10, tech, "$", None, None, None, None)),
             ("THREAD WITH A DRILL", th, thread_op("DRILL ONLY", drill)),
             ("THREAD TOOL WRONG SIZE", th, thread_op("BGF 12", bgf12))])

    # ---- hostile values for the new shapes: a clean STEPNC-103/101, never a crash or hang ----
    p = program("hostile-shapes", "zero, negative, infinite and out-of-range sizes and angles for slots, steps and threads")
    tech = p.tech(0.02, -40.0)
    sink = p.tool("COUNTERSINK 16 X 90", "COUNTERSINK", 16, edge_length=12.0, tip=45.0)
    zero_tool = p.tool("NO SIZE", "BALL_ENDMILL", 0, edge_length=12.0, edge_radius=0.0)
    ball6 = p.tool("BALL 6", "BALL_ENDMILL", 6, edge_length=15.0, edge_radius=3.0)
    mill10 = mill(p, 10, 20)
    bgf14 = p.tool("THREAD DRILL MILL 14", "MILLING_THREADING_TOOL", 14, edge_length=40.0, tip=31.0)
    radiused = p.add("RADIUSED_SLOT_END_TYPE()")
    flat_angle = slot_feature(p, "VEE 180", 0, 0, line_path(p, 40), vee_profile(p, 180.0, 0.0, 0.0), [radiused, radiused], 5)
    reflex = slot_feature(p, "VEE 200", 0, 0, line_path(p, 40), vee_profile(p, 200.0, 0.0, 0.0), [radiused, radiused], 5)
    wide = slot_feature(p, "ARC 270", 0, 0, line_path(p, 40),
                        p.add(f"PARTIAL_CIRCULAR_PROFILE($,{p.length(6)},270.0)"), [radiused, radiused], 3)
    zero_width = slot_feature(p, "WIDTH 0", 0, 0, line_path(p, 40),
                              p.add(f"SQUARE_U_PROFILE($,{p.length(0)},{p.length(0)},90.0,{p.length(0)},90.0)"),
                              [radiused, radiused], 3)
    negative = slot_feature(p, "WIDTH -8", 0, 0, line_path(p, 40), p.add(f"ROUNDED_U_PROFILE($,{p.length(-8)})"),
                            [radiused, radiused], 3)
    # Non-finite reals (1.E400) are refused by the reader (P21-008) before any generator runs.
    huge_arc = slot_feature(p, "ARC RADIUS 1E300", 0, 0, line_path(p, 40),
                            p.add(f"PARTIAL_CIRCULAR_PROFILE($,{p.length(1e300)},120.0)"), [radiused, radiused], 3)
    arc120 = p.add(f"PARTIAL_CIRCULAR_PROFILE($,{p.length(6)},120.0)")
    round_slot = slot_feature(p, "ROUND 12", 0, 0, line_path(p, 40), arc120, [radiused, radiused], 3)
    huge_path = slot_feature(p, "VEE 1E9 LONG", 0, 0, line_path(p, 1e9), vee_profile(p, 90), [radiused, radiused], 5)
    no_ends = slot_feature(p, "NO ENDS", 0, 0, line_path(p, 40), vee_profile(p, 90), [], 5)
    loop_line = slot_feature(p, "LOOP ON A LINE", 0, 0, line_path(p, 40), vee_profile(p, 90),
                             [p.add("LOOP_SLOT_END_TYPE()")], 5)
    huge_step = step_feature(p, "STEP 1E12 WIDE", 0, 0, 60, (0, 1, 0), (1e12, 0, -8), 8)
    no_wall = step_feature(p, "STEP NO WALL", 0, 0, 60, (0, 1, 0), None, 8)
    h = hole(p, 0, 0, 14, 20)
    no_pitch = thread_feature(p, "ZERO THREADS", 0, 0, h, 16, 0.0, "1/MM", "RIGHT", 20)
    odd_unit = thread_feature(p, "PITCH UNIT", 0, 0, h, 16, 2.0, "MM", "RIGHT", 20)
    tiny_pitch = thread_feature(p, "1E9 THREADS", 0, 0, h, 16, 1e9, "1/MM", "RIGHT", 20)
    centre = p.add("CENTER_MILLING($,.T.)")
    cp = p.add("CONTOUR_PARALLEL($,.T.,$,.CLIMB.)")

    def op(name, tool, strategy=centre):
        return bs(p, "FINISH", name, tool, tech, strategy, None, None, None, None)

    def thread_op(name):
        return p.add(f"THREAD_DRILLING($,$,'{name}',3.000,$,{bgf14},{tech},{p.functions()},$,$,$,$,$,$,.F.)")
    p.write([("VEE 180 DEG", flat_angle, op("A", sink)), ("VEE 200 DEG", reflex, op("B", sink)),
             ("ARC 270 DEG", wide, op("C", ball6)), ("ZERO WIDTH", zero_width, op("D", mill10)),
             ("NEGATIVE WIDTH", negative, op("E", ball6)), ("HUGE RADIUS", huge_arc, op("F", ball6)),
             ("TOOL RADIUS 0", round_slot, op("G", zero_tool)),
             ("HUGE SLOT", huge_path, op("H", sink)), ("NO END CONDITIONS", no_ends, op("I", sink)),
             ("LOOP ON A LINE", loop_line, op("J", sink)),
             ("HUGE STEP", huge_step, op("K", mill10, cp)), ("STEP WITHOUT WALL", no_wall, op("L", mill10, cp)),
             ("ZERO THREADS", no_pitch, thread_op("M")), ("PITCH UNIT", odd_unit, thread_op("N")),
             ("TINY PITCH", tiny_pitch, thread_op("O"))])

    # ---- hostile numbers: refused by the motion limit before anything is built ----
    p = program("hostile", "stepover, axial depth and helix angle that would need billions of motions")
    t, tech = mill(p, 10, 20), p.tech(0.03, -40.0)
    pocket = rect_pocket(p, 0, 0, 60, 40, 10, 8)
    cp = p.add("CONTOUR_PARALLEL($,.T.,.CCW.,$)")
    flat = p.add("PLUNGE_HELIX($,3.0,0.0000000001)")
    p.write([("TINY STEPOVER", pocket, bs(p, "ROUGH", "R1", t, tech, cp, 5.0, 1e-9, 0.0, 0.0)),
             ("TINY AXIAL", pocket, bs(p, "ROUGH", "R2", t, tech, cp, 1e-9, None, 0.0, 0.0)),
             ("FLAT HELIX", pocket, bs(p, "ROUGH", "R3", t, tech, cp, 5.0, None, 0.0, 0.0, flat))])

    # ---- what is not generated: each a STEPNC-101 naming the instances ----
    p = program("unsupported", "features and strategies the generator does not implement")
    mill10, tech = mill(p, 10, 20), p.tech(0.03, -40.0)
    vee = p.add(f"VEE_PROFILE($,{p.length(2)},60.0,0.0)")
    path = p.add(f"LINEAR_PATH($,{p.length(30)},{p.direction(1, 0, 0)})")
    vslot = p.add(f"SLOT('VEE SLOT',#4,(),{p.placement()},{p.plane('D', -3)},{path},{vee},())")
    poly = p.add(f"POLYLINE('',({p.point(0, 0, 0)},{p.point(30, 0, 0)},{p.point(0, 20, 0)},{p.point(0, 0, 0)}))")
    gcp = p.add(f"GENERAL_CLOSED_PROFILE($,{poly})")
    b = p.add("PLANAR_POCKET_BOTTOM_CONDITION()")
    tri = p.add(f"CLOSED_POCKET('TRIANGLE',#4,(),{p.placement(50, 0, 0)},{p.plane('D', -3)},(),5.0,{b},$,$,{gcp})")
    step = step_feature(p, "STEP", 100, 0, 40, (0, 1, 0), (20, 0, -5), 5, angle=120.0)
    rect = rect_pocket(p, 0, 60, 40, 30, 5, 6)
    spiral = p.add("CONTOUR_SPIRAL($,.T.,.CW.,$)")
    air = p.add("AP_RETRACT_ANGLE($,45.0,5.0)")
    cp = p.add("CONTOUR_PARALLEL($,.T.,.CW.,$)")
    bi = p.add(f"BIDIRECTIONAL_MILLING($,.T.,{p.direction(1, 0, 0)},$,$)")
    side = p.add(f"SIDE_ROUGH_MILLING($,$,'SIDE',5.000,$,{mill10},{tech},{p.functions()},$,$,$,{bi},5.0,2.0,0.5)")
    tee = p.add(f"TEE_PROFILE($,90.0,90.0,{p.length(20)},{p.length(4)},{p.length(0)},{p.length(8)},"
                f"{p.length(6)},{p.length(6)})")
    tslot = slot_feature(p, "TEE SLOT", 0, 120, line_path(p, 40), tee,
                         [p.add("OPEN_SLOT_END_TYPE()"), p.add("OPEN_SLOT_END_TYPE()")], 10)
    ball8 = p.tool("BALL 8", "BALL_ENDMILL", 8, edge_length=16.0, edge_radius=4.0)
    w20 = p.add(f"WOODRUFF_SLOT_END_TYPE({p.length(20)})")
    keyway = slot_feature(p, "KEYWAY", 0, 150, line_path(p, 30),
                          p.add(f"ROUNDED_U_PROFILE($,{p.length(8)})"), [w20, w20], 5)
    steep = p.add("PLUNGE_RAMP($,10.0)")
    p.write([("VEE SLOT", vslot, bs(p, "ROUGH", "VEE", mill10, tech, cp, 1.0, None, 0.0, 0.0)),
             ("TEE SLOT", tslot, bs(p, "ROUGH", "TEE", mill10, tech, cp, 1.0, None, 0.0, 0.0)),
             ("WOODRUFF END WITH A RAMP", keyway, bs(p, "FINISH", "KEY", ball8, tech, "$", None, None,
                                                     None, None, steep)),
             ("SLOPED GENERAL POCKET", tri, bs(p, "ROUGH", "TRI", mill10, tech, cp, 1.0, None, 0.0, 0.0)),
             ("SLOPED STEP WALL", step, bs(p, "ROUGH", "STEP", mill10, tech, cp, 1.0, None, 0.0, 0.0)),
             ("SPIRAL", rect, bs(p, "ROUGH", "SPIRAL", mill10, tech, spiral, 1.0, None, 0.0, 0.0)),
             ("AIR APPROACH", rect, bs(p, "ROUGH", "AIR", mill10, tech, cp, 1.0, None, 0.0, 0.0, air)),
             ("SIDE MILLING BIDIRECTIONAL", rect, side)])

    # ---- round holes ----
    p = program("holes-cycles", "round holes: drilling, center drilling, peck, reaming, boring, tapping")
    drill = p.tool("DRILL 8", "TWIST_DRILL", 8, edge_length=40.0, tip=31.0)
    centre = p.tool("CENTER DRILL 4", "CENTER_DRILL", 4, edge_length=6.0, tip=45.0)
    reamer = p.tool("REAMER 10", "REAMER", 10, edge_length=30.0)
    bore = p.tool("BORING BAR 9.5", "BORING_TOOL", 9.5, edge_length=30.0)
    tap = p.tool("TAP M10", "TAP", 10, edge_length=25.0)
    lefttap = p.tool("TAP M10 LH", "TAP", 10, edge_length=25.0, hand=".LEFT.")
    h1 = hole(p, 10, 10, 8, 15)
    h2 = hole(p, 30, 10, 10, 20, "FLAT_HOLE_BOTTOM()")
    h3 = hole(p, 50, 10, 10, 12, "CONICAL_HOLE_BOTTOM(118.0,$)")
    slow = p.tech(0.005, -15.0)
    tap_tech = p.tech(0.0125, -8.333333333333334)  # 750 mm/min at 500 rpm: M10 × 1.5
    steps = [
        ("CENTER DRILL", h1, drill_op(p, "CENTER_DRILLING", "CENTER", centre, slow, cutting_depth="3.000")),
        ("DRILL THROUGH", h1, drill_op(p, "DRILLING", "DRILL", drill, p.tech(0.01, -20.0), dwell="0.5")),
        ("PECK EVEN", h2, drill_op(p, "MULTISTEP_DRILLING", "PECK", drill, p.tech(0.01, -20.0),
                                   extra=",1.000,4.000,4.000,$")),
        ("PECK FIRST DEEPER", h3, drill_op(p, "MULTISTEP_DRILLING", "PECK 2", drill, p.tech(0.01, -20.0),
                                           extra=",0.000,6.000,3.000,0.2")),
        ("REAM", h2, drill_op(p, "REAMING", "REAM", reamer, slow, extra=",.F.,$,$")),
        ("BORE", h2, drill_op(p, "BORING", "BORE", bore, slow, extra=",.T.,$,$")),
        ("TAP", h2, drill_op(p, "TAPPING", "TAP", tap, tap_tech, extra=",.F.")),
        ("TAP LEFT", h3, drill_op(p, "TAPPING", "TAP LH", lefttap, p.tech(0.0125, 8.333333333333334),
                                  dwell="0.3", extra=",.T.")),
    ]
    p.write(steps)

    p = program("holes-pointed-bottoms", "a pointed drill in bottoms it cannot finish: notes, and ncpost verify reports the floor it leaves")
    drill = p.tool("DRILL 8", "TWIST_DRILL", 8, edge_length=40.0, tip=31.0)
    h4 = hole(p, 70, 10, 10, 12, "SPHERICAL_HOLE_BOTTOM(" + p.length(5.0) + ")")
    h5 = hole(p, 90, 10, 10, 12, "FLAT_WITH_RADIUS_HOLE_BOTTOM(" + p.length(1.0) + ")")
    p.write([("DRILL SPHERICAL", h4, drill_op(p, "DRILLING", "DRILL 2", drill, p.tech(0.01, -20.0))),
             ("DRILL FLAT RADIUS", h5, drill_op(p, "DRILLING", "DRILL 3", drill, p.tech(0.01, -20.0)))])

    p = program("holes-strategy", "drilling with reduced feed and speed at start and end, dwell, feed on retract")
    drill = p.tool("DRILL 10", "TWIST_DRILL", 10, edge_length=50.0, tip=31.0)
    h = hole(p, 0, 0, 10, 30)
    st = p.add("DRILLING_TYPE_STRATEGY(0.8,0.5,3.000,0.6,0.4,5.000)")
    p.write([("DRILL STRATEGY", h, drill_op(p, "DRILLING", "DRILL", drill, p.tech(0.02, -15.0),
                                            dwell="1.0", strategy=st, retract_ratio="2.0"))])

    # ---- wrong tools and data (each a documented diagnostic) ----
    p = program("wrong-tools", "tools that cannot make their features")
    big = mill(p, 20, 30)
    short = mill(p, 10, 3)
    tech = p.tech(0.03, -30.0)
    pocket = rect_pocket(p, 0, 0, 60, 40, 10, 8)
    s = p.add("CONTOUR_PARALLEL(0.5,.T.,.CCW.,$)")
    once = p.add("CONTOUR_PARALLEL(0.5,.F.,.CCW.,$)")
    wide = p.add("PLUNGE_HELIX($,30.0,5.0)")
    drill = p.tool("DRILL 12", "TWIST_DRILL", 12, edge_length=40.0, tip=31.0)
    shortdrill = p.tool("STUB DRILL 6", "TWIST_DRILL", 6, edge_length=10.0, tip=31.0)
    reamer = p.tool("REAMER 9", "REAMER", 9, edge_length=30.0)
    pointy = p.tool("DRILL 8 140DEG", "TWIST_DRILL", 8, edge_length=40.0, tip=20.0)
    h = hole(p, 50, 0, 10, 20)
    cone = hole(p, 70, 0, 8, 10, "CONICAL_HOLE_BOTTOM(118.0,$)")
    sharp = rect_pocket(p, 100, 0, 30, 30, 5, None)
    fill = rect_pocket(p, 140, 0, 30, 30, 4, 5, floor=p.length(3.0, 0.05))
    bull = p.tool("BULLNOSE 10 R1", "BULLNOSE_ENDMILL", 10, edge_length=20.0, edge_radius=1.0)
    p.write([
        ("CORNER TOO SMALL", pocket, bs(p, "ROUGH", "ROUGH BIG", big, tech, s, 5.0, None, 0.5, 0.5)),
        ("EDGE TOO SHORT", pocket, bs(p, "ROUGH", "ROUGH SHORT", short, tech, s, 5.0, None, 0.5, 0.5)),
        ("ONE PASS FORBIDS STEPS", pocket, bs(p, "ROUGH", "ROUGH ONCE", short, tech, once, 2.0, None, 0.5, 0.5)),
        ("HELIX TOO WIDE", pocket, bs(p, "ROUGH", "ROUGH HELIX", mill(p, 10, 30), tech, s, 5.0, None, 0.5, 0.5, wide)),
        ("SHARP CORNERS", sharp, bs(p, "FINISH", "FINISH SHARP", mill(p, 6, 30), tech, s, 5.0, None, None, None)),
        ("FILLET TOO LARGE", fill, bs(p, "FINISH", "FINISH FILLET", bull, tech, s, None, None, None, None)),
        ("DRILL TOO BIG", h, drill_op(p, "DRILLING", "DRILL BIG", drill, tech)),
        ("DRILL TOO SHORT", h, drill_op(p, "DRILLING", "DRILL SHORT", shortdrill, tech)),
        ("REAMER WRONG SIZE", h, drill_op(p, "REAMING", "REAM", reamer, tech, extra=",.F.,$,$")),
        ("POINT ANGLE", cone, drill_op(p, "DRILLING", "DRILL POINT", pointy, tech)),
        ("TAP TURNS BACKWARDS", h, drill_op(p, "TAPPING", "TAP", p.tool("TAP M10", "TAP", 10, edge_length=25.0),
                                            p.tech(0.0125, 8.333333333333334), extra=",.F.")),
    ])


# ---- general profiles (polylines, composite curves of trimmed lines and circles, n-gons) ----
def polyline(p, pts, close=True):
    ids = [p.point(x, y, 0) for x, y in pts]
    if close:
        ids.append(ids[0])
    return p.add(f"POLYLINE('',({','.join(ids)}))")


def trimmed_line(p, a, b):
    dx, dy = b[0] - a[0], b[1] - a[1]
    length = (dx * dx + dy * dy) ** 0.5
    vec = p.add(f"VECTOR('',{p.direction(dx / length, dy / length, 0)},{length:.3f})")
    line = p.add(f"LINE('',{p.point(a[0], a[1], 0)},{vec})")
    return p.add(f"TRIMMED_CURVE('',{line},({p.point(a[0], a[1], 0)}),({p.point(b[0], b[1], 0)}),"
                 ".T.,.CARTESIAN.)")


def trimmed_arc(p, centre, radius, a, b, ccw):
    circle = p.add(f"CIRCLE('',{p.placement(centre[0], centre[1], 0)},{radius:.6f})")
    sense = ".T." if ccw else ".F."
    return p.add(f"TRIMMED_CURVE('',{circle},({p.point(a[0], a[1], 0)}),({p.point(b[0], b[1], 0)}),"
                 f"{sense},.CARTESIAN.)")


def composite(p, segments):
    ids = [p.add(f"COMPOSITE_CURVE_SEGMENT(.CONTINUOUS.,.T.,{s})") for s in segments]
    return p.add(f"COMPOSITE_CURVE('',({','.join(ids)}),.F.)")


def general_pocket(p, name, x, y, curve, depth, corner=None, floor="$",
                   bottom="PLANAR_POCKET_BOTTOM_CONDITION()", profile=None):
    prof = profile or p.add(f"GENERAL_CLOSED_PROFILE($,{curve})")
    b = p.add(bottom)
    c = p.length(corner) if corner is not None else "$"
    return p.add(f"CLOSED_POCKET('{name}',#4,(),{p.placement(x, y, 0)},"
                 f"{p.plane('POCKET DEPTH', -depth)},(),$,{b},{floor},{c},{prof})")


def ngon(p, diameter, sides, circumscribed=True):
    flag = ".T." if circumscribed else ".F."
    return p.add(f"NGON_CLOSED_PROFILE($,{p.length(diameter)},{sides},{flag})")


def open_pocket(p, name, x, y, walls, depth, corner=None, wall_boundary="$"):
    prof = p.add(f"GENERAL_PROFILE($,{walls})")
    b = p.add("PLANAR_POCKET_BOTTOM_CONDITION()")
    c = p.length(corner) if corner is not None else "$"
    return p.add(f"OPEN_POCKET('{name}',#4,(),{p.placement(x, y, 0)},"
                 f"{p.plane('POCKET DEPTH', -depth)},(),$,{b},$,{c},{prof},{wall_boundary})")


def outside(p, name, x, y, boundary, depth):
    path = p.add(f"LINEAR_PATH($,{p.length(depth)},{p.direction(0, 0, -1)})")
    return p.add(f"GENERAL_OUTSIDE_PROFILE('{name}',#4,(),{p.placement(x, y, 0)},"
                 f"{p.plane('PROFILE DEPTH', -depth)},{path},{boundary})")


def side_op(p, kind, name, tool, tech, strategy, axial, allowance, approach="$"):
    return p.add(f"SIDE_{kind}_MILLING($,$,'{name}',5.000,$,{tool},{tech},{p.functions()},$,"
                 f"{approach},$,{strategy},{axial:.3f},$,{allowance:.3f})")


def star(outer, inner, points=5):
    import math
    pts = []
    for k in range(2 * points):
        r = outer if k % 2 == 0 else inner
        t = math.pi / 2 + math.pi * k / points
        pts.append((round(r * math.cos(t), 3), round(r * math.sin(t), 3)))
    return pts


def general_cases():
    p = program("pocket-polyline-l", "L-shaped polyline pocket (orthogonal_radius 6): rings, bidirectional floor, side finish")
    t, tech = mill(p, 10, 20), p.tech(0.03, -40.0)
    ell = polyline(p, [(0, 0), (60, 0), (60, 25), (25, 25), (25, 50), (0, 50)])
    f = general_pocket(p, "L POCKET", 10, 10, ell, 8, corner=6)
    cp = p.add("CONTOUR_PARALLEL(0.4,.T.,$,.CLIMB.)")
    bi = p.add(f"BIDIRECTIONAL_MILLING(0.3,.T.,{p.direction(1, 0, 0)},.LEFT.,$)")
    p.write([("L ROUGH", f, bs(p, "ROUGH", "L R", t, tech, cp, 4.0, None, 0.5, 0.3)),
             ("L FLOOR", f, bs(p, "FINISH", "L F", t, tech, bi, 8.0, None, 0.5, None)),
             ("L WALLS", f, side_op(p, "FINISH", "L W", t, tech, cp, 8.0, 0.0))])

    p = program("pocket-composite", "pocket bounded by a composite curve: lines, a convex and a concave arc; ramp entry, then bidirectional-contour")
    t, tech = mill(p, 8, 20), p.tech(0.03, -40.0)
    d_shape = composite(p, [
        trimmed_line(p, (0, 0), (40, 0)),
        trimmed_arc(p, (40, 20), 20, (40, 0), (40, 40), True),
        trimmed_line(p, (40, 40), (0, 40)),
        trimmed_arc(p, (-21, 20), 29, (0, 40), (0, 0), False)])
    f = general_pocket(p, "D POCKET", 0, 0, d_shape, 6, corner=5)
    cp = p.add("CONTOUR_PARALLEL(0.5,.T.,.CCW.,$)")
    ramp = p.add("PLUNGE_RAMP($,5.0)")
    bc = p.add(f"BIDIRECTIONAL_CONTOUR(0.3,.T.,{p.direction(0, 1, 0)},.RIGHT.,.CCW.,$)")
    p.write([("D ROUGH", f, bs(p, "ROUGH", "D R", t, tech, cp, 3.0, None, 0.5, 0.2, ramp)),
             ("D FINISH", f, bs(p, "FINISH", "D F", t, tech, bc, 6.0, None, None, None))])

    p = program("pocket-star", "a concave star, and twin lobes joined by a neck: their offsets split into one island per lobe, each machined from its own innermost ring")
    t, tech = mill(p, 10, 25), p.tech(0.03, -40.0)
    f = general_pocket(p, "STAR", 0, 0, polyline(p, star(45, 20)), 5, corner=6)
    twin = general_pocket(p, "TWIN LOBES", 0, 100, polyline(p, [(0, 0), (40, 0), (40, 12), (60, 12), (60, 0), (100, 0), (100, 40), (60, 40), (60, 28), (40, 28), (40, 40), (0, 40)]), 6, corner=6)
    cp = p.add("CONTOUR_PARALLEL(0.5,.T.,$,.CONVENTIONAL.)")
    p.write([("STAR ROUGH", f, bs(p, "ROUGH", "STAR R", t, tech, cp, 5.0, None, 0.0, 0.0)),
             ("TWIN ROUGH", twin, bs(p, "ROUGH", "TWIN R", t, tech, cp, 3.0, None, 0.0, 0.0))])

    p = program("pocket-ngon", "hexagonal pocket (across flats): one-way lines along y, then contour-bidirectional")
    t, tech = mill(p, 10, 20), p.tech(0.03, -40.0)
    f = general_pocket(p, "HEXAGON", 0, 0, None, 4, corner=6, profile=ngon(p, 50, 6, False))
    uni = p.add(f"UNIDIRECTIONAL_MILLING(0.3,.T.,{p.direction(0, 1, 0)},.CLIMB.)")
    cb = p.add(f"CONTOUR_BIDIRECTIONAL(0.3,.T.,{p.direction(1, 0, 0)},$,.CW.,$)")
    p.write([("HEX UNIDIRECTIONAL", f, bs(p, "ROUGH", "HEX U", t, tech, uni, 2.0, None, 0.3, 0.2)),
             ("HEX CONTOUR BIDIRECTIONAL", f, bs(p, "FINISH", "HEX CB", t, tech, cb, 4.0, None, None, None))])

    p = program("open-pocket", "open pockets: U-shaped walls open on one side (rings run out past it), and walls with an arc (lines run out past it)")
    t, tech = mill(p, 10, 20), p.tech(0.03, -40.0)
    walls = polyline(p, [(50, -20), (0, -20), (0, 20), (50, 20)], close=False)
    info = p.add(f"GENERAL_PROFILE($,{polyline(p, [(50, 20), (50, -20)], close=False)})")
    f1 = open_pocket(p, "OPEN U", 0, 0, walls, 6, corner=6, wall_boundary=info)
    bay = composite(p, [
        trimmed_line(p, (130, 0), (100, 0)),
        trimmed_arc(p, (100, 20), 20, (100, 0), (100, 40), False),
        trimmed_line(p, (100, 40), (130, 40))])
    f2 = open_pocket(p, "OPEN ARC", 0, 0, bay, 4)
    cp = p.add("CONTOUR_PARALLEL(0.5,.T.,$,.CLIMB.)")
    bi = p.add(f"BIDIRECTIONAL_MILLING(0.3,.T.,{p.direction(1, 0, 0)},.LEFT.,$)")
    p.write([("OPEN U ROUGH", f1, bs(p, "ROUGH", "OU", t, tech, cp, 3.0, None, 0.0, 0.0)),
             ("OPEN ARC LINES", f2, bs(p, "ROUGH", "OA", t, tech, bi, 4.0, None, 0.0, 0.0))])

    p = program("outside-general", "general outside profiles: a composite boss with a concave arc, a polyline pentagon")
    t, tech = mill(p, 12, 25), p.tech(0.03, -40.0)
    notch = composite(p, [
        trimmed_line(p, (0, 0), (40, 0)),
        trimmed_line(p, (40, 0), (40, 30)),
        trimmed_line(p, (40, 30), (30, 30)),
        trimmed_arc(p, (20, 40), 200 ** 0.5, (30, 30), (10, 30), False),
        trimmed_line(p, (10, 30), (0, 30)),
        trimmed_line(p, (0, 30), (0, 0))])
    boss = outside(p, "NOTCHED BOSS", 0, 0, p.add(f"GENERAL_CLOSED_PROFILE($,{notch})"), 8)
    penta = outside(p, "PENTAGON", 100, 0, polyline_profile(p, [(20, 0), (6.18, 19.021), (-16.18, 11.756), (-16.18, -11.756), (6.18, -19.021)]), 5)
    climb = p.add("CONTOUR_PARALLEL($,.T.,$,.CLIMB.)")
    conv = p.add("CONTOUR_PARALLEL($,.T.,$,.CONVENTIONAL.)")
    p.write([("BOSS ROUGH", boss, side_op(p, "ROUGH", "BOSS R", t, tech, climb, 4.0, 0.5)),
             ("BOSS FINISH", boss, side_op(p, "FINISH", "BOSS F", t, tech, climb, 8.0, 0.0)),
             ("PENTAGON FINISH", penta, side_op(p, "FINISH", "PENTA F", t, tech, conv, 2.5, 0.0))])

    p = program("pocket-radiused-bottom", "a round pocket whose floor is the half ball of its radius (RADIUSED_POCKET_BOTTOM_CONDITION), made by a ball of that radius down its axis")
    ball = p.tool("BALL 20", "BALL_ENDMILL", 20, edge_length=30.0, edge_radius=10.0)
    tech = p.tech(0.02, -30.0)
    bottom = f"RADIUSED_POCKET_BOTTOM_CONDITION({p.point(0, 0, -5)},{p.length(10, 0.02)})"
    prof = p.add(f"CIRCULAR_CLOSED_PROFILE($,{p.length(20, 0.02)})")
    b = p.add(bottom)
    f = p.add(f"CLOSED_POCKET('BALL POCKET',#4,(),{p.placement(20, 20, 0)},"
              f"{p.plane('POCKET DEPTH', -15)},(),$,{b},$,$,{prof})")
    ax = p.add("PLUNGE_TOOLAXIS($)")
    cp = p.add("CONTOUR_PARALLEL($,.T.,$,.CLIMB.)")
    p.write([("BALL POCKET", f, bs(p, "FINISH", "BALL", ball, tech, cp, 5.0, None, None, None, ax))])

    # ---- wrong tools for general profiles (STEPNC-102 naming the tool, operation and feature) ----
    p = program("wrong-tools-general", "tools that cannot make general profiles")
    t, tech = mill(p, 10, 20), p.tech(0.03, -30.0)
    cp = p.add("CONTOUR_PARALLEL(0.5,.T.,.CCW.,$)")
    sharp = general_pocket(p, "SHARP L", 0, 0, polyline(p, [(0, 0), (60, 0), (60, 25), (25, 25), (25, 50), (0, 50)]), 5)
    small_arc = composite(p, [
        trimmed_line(p, (0, 0), (40, 0)),
        trimmed_arc(p, (40, 3), 3, (40, 0), (40, 6), True),
        trimmed_line(p, (40, 6), (0, 6)),
        trimmed_arc(p, (0, 3), 3, (0, 6), (0, 0), True)])
    narrow = general_pocket(p, "NARROW ENDS", 100, 0, small_arc, 5)
    dumbbell = general_pocket(p, "DUMBBELL", 0, 100, polyline(p, [(0, 0), (30, 0), (30, 12), (60, 12), (60, 0), (90, 0), (90, 30), (60, 30), (60, 18), (30, 18), (30, 30), (0, 30)]), 5, corner=6)
    tiny = general_pocket(p, "TINY HEXAGON", 200, 0, None, 5, corner=6, profile=ngon(p, 8, 6))
    ell = general_pocket(p, "L POCKET", 0, 300, polyline(p, [(0, 0), (60, 0), (60, 25), (25, 25), (25, 50), (0, 50)]), 5, corner=6)
    big_helix = p.add("PLUNGE_HELIX($,20.0,5.0)")
    ell_boss = outside(p, "L BOSS", 0, 200, polyline_profile(p, [(0, 0), (40, 0), (40, 15), (15, 15), (15, 40), (0, 40)]), 5)
    half_ball = p.add(f"RADIUSED_POCKET_BOTTOM_CONDITION({p.point(0, 0, -5)},{p.length(10, 0.02)})")
    round_prof = p.add(f"CIRCULAR_CLOSED_PROFILE($,{p.length(20, 0.02)})")
    ball_pocket = p.add(f"CLOSED_POCKET('BALL POCKET',#4,(),{p.placement(300, 0, 0)},"
                        f"{p.plane('POCKET DEPTH', -15)},(),$,{half_ball},$,$,{round_prof})")
    dish = p.add(f"RADIUSED_POCKET_BOTTOM_CONDITION({p.point(0, 0, 40)},{p.length(50)})")
    dish_pocket = p.add(f"CLOSED_POCKET('DISH',#4,(),{p.placement(300, 100, 0)},"
                        f"{p.plane('POCKET DEPTH', -10)},(),$,{dish},$,$,{round_prof})")
    p.write([
        ("SHARP CORNERS", sharp, bs(p, "ROUGH", "R SHARP", t, tech, cp, 5.0, None, 0.5, 0.0)),
        ("ARC TOO TIGHT", narrow, bs(p, "ROUGH", "R NARROW", t, tech, cp, 5.0, None, 0.0, 0.0)),
        ("NECK TOO NARROW", dumbbell, bs(p, "ROUGH", "R NECK", t, tech, cp, 5.0, None, 0.0, 0.0)),
        # Corners of 6 on sides of 4: the outline is inconsistent (STEPNC-103). A general pocket
        # whose corners fit the tool and whose sides fit its corners is never too small.
        ("POCKET TOO SMALL", tiny, bs(p, "ROUGH", "R TINY", t, tech, cp, 5.0, None, 0.0, 0.0)),
        ("HELIX TOO WIDE", ell, bs(p, "ROUGH", "R HELIX", t, tech, cp, 5.0, None, 0.0, 0.0, big_helix)),
        ("CONCAVE CORNER OUTSIDE", ell_boss, side_op(p, "FINISH", "S L", t, tech, cp, 5.0, 0.0)),
        # A flat end mill in a pocket whose floor is a half ball: STEPNC-102 naming both.
        ("FLAT TOOL IN BALL POCKET", ball_pocket, bs(p, "FINISH", "F BALL", mill(p, 20, 30), tech, cp, 5.0, None, None, None)),
        # A shallow spherical dish: 3D surface finishing, STEPNC-101.
        ("SPHERICAL DISH", dish_pocket, bs(p, "FINISH", "F DISH", t, tech, cp, 5.0, None, None, None)),
    ])

    # ---- hostile general profiles: each a clean STEPNC-103 (or STEPNC-011), never a crash ----
    p = program("hostile-general", "self-intersecting, zero-area, open, far away and gapped profiles; an n-gon of a billion sides")
    t, tech = mill(p, 6, 20), p.tech(0.03, -30.0)
    cp = p.add("CONTOUR_PARALLEL(0.5,.T.,.CCW.,$)")
    bowtie = general_pocket(p, "BOW TIE", 0, 0, polyline(p, [(0, 0), (40, 30), (40, 0), (0, 30)]), 3, corner=4)
    flat = general_pocket(p, "ZERO AREA", 0, 0, polyline(p, [(0, 0), (20, 0), (40, 0)]), 3, corner=4)
    unclosed = general_pocket(p, "NOT CLOSED", 0, 0, polyline(p, [(0, 0), (40, 0), (40, 30), (0, 30)], close=False), 3, corner=4)
    far = general_pocket(p, "FAR AWAY", 0, 0, polyline(p, [(0, 0), (1e9, 0), (1e9, 30), (0, 30)]), 3, corner=4)
    gap = composite(p, [trimmed_line(p, (0, 0), (40, 0)), trimmed_line(p, (40, 1), (40, 30)),
                        trimmed_line(p, (40, 30), (0, 30)), trimmed_line(p, (0, 30), (0, 0))])
    gapped = general_pocket(p, "GAPPED", 0, 0, gap, 3, corner=4)
    billion = general_pocket(p, "BILLION SIDES", 0, 0, None, 3, profile=ngon(p, 50, 1000000000))
    steps = [(n, f, bs(p, "ROUGH", n, t, tech, cp, 3.0, None, 0.0, 0.0))
             for n, f in [("BOW TIE", bowtie), ("ZERO AREA", flat), ("NOT CLOSED", unclosed),
                          ("FAR AWAY", far), ("GAPPED", gapped), ("BILLION SIDES", billion)]]
    p.write(steps)


def polyline_profile(p, pts):
    return p.add(f"GENERAL_CLOSED_PROFILE($,{polyline(p, pts)})")


# ---- geometry other systems write (issue 17, parts 4 and 5) ----
def rot(deg):
    import math
    return (round(math.cos(math.radians(deg)), 6), round(math.sin(math.radians(deg)), 6), 0)


def bspline(p, degree, pts, knots=None, kind="B_SPLINE_CURVE_WITH_KNOTS"):
    """A B-spline in the xy plane as CAD toolkits write it: clamped knots (uniform inside) unless
    given, or a BEZIER_CURVE / QUASI_UNIFORM_CURVE whose knots are implicit."""
    ids = ",".join(p.point(x, y, 0) for x, y in pts)
    if kind != "B_SPLINE_CURVE_WITH_KNOTS":
        return p.add(f"{kind}('',{degree},({ids}),.UNSPECIFIED.,.F.,.F.)")
    if knots is None:
        inner = len(pts) - degree - 1
        values = [k / (inner + 1) for k in range(inner + 2)]
        mult = [degree + 1] + [1] * inner + [degree + 1]
    else:
        values, mult = knots
    return p.add(f"{kind}('',{degree},({ids}),.UNSPECIFIED.,.F.,.F.,({','.join(str(m) for m in mult)}),"
                 f"({','.join(f'{v:.6g}' for v in values)}),.UNSPECIFIED.)")


def section_cases():
    """Slots whose swept shape is a GENERAL_PROFILE (issue 17, part 4): the section in the
    profile's xy plane, x across the slot (left of the travel), y up, its top at y = 0."""
    p = program("slot-general-section", "slots whose section is a general profile: a symmetric B-spline with radiused ends (a ball in rings, two levels), an asymmetric Bezier curve between open ends (a ball in straight passes), a stepped polyline with a radiused and an open end (an end mill in rings), the Bezier curve round a complete circle (a ball in circles)")
    ball6 = p.tool("BALL 6", "BALL_ENDMILL", 6, edge_length=15.0, edge_radius=3.0)
    ball4 = p.tool("BALL 4", "BALL_ENDMILL", 4, edge_length=12.0, edge_radius=2.0)
    mill6 = mill(p, 6, 15)
    tech = p.tech(0.02, -50.0)
    radiused, opened = p.add("RADIUSED_SLOT_END_TYPE()"), p.add("OPEN_SLOT_END_TYPE()")
    ogee = bspline(p, 3, [(-10, 0), (-8, -4), (-3, -6), (3, -6), (8, -4), (10, 0)])
    s1 = slot_feature(p, "SPLINE GROOVE", 0, 0, line_path(p, 40), p.add(f"GENERAL_PROFILE($,{ogee})"),
                      [radiused, radiused], 5.875)
    lopsided = bspline(p, 3, [(-5, 0), (-5, -6), (3, -6), (9, 0)], kind="BEZIER_CURVE")
    s2 = slot_feature(p, "BEZIER CHANNEL", 0, 40, line_path(p, 30, (0, 1, 0)),
                      p.add(f"GENERAL_PROFILE($,{lopsided})"), [opened, opened], 4.5)
    stepped = polyline(p, [(-9, 0), (-9, -2), (-4, -2), (-4, -5), (4, -5), (4, -2), (9, -2), (9, 0)], close=False)
    s3 = slot_feature(p, "STEPPED SLOT", 40, 60, line_path(p, 30), p.add(f"GENERAL_PROFILE($,{stepped})"),
                      [radiused, opened], 5)
    ring = p.add(f"COMPLETE_CIRCULAR_PATH($,{p.length(20)})")
    s4 = slot_feature(p, "BEZIER RING", 110, 0, ring, p.add(f"GENERAL_PROFILE($,{lopsided})"),
                      [p.add("LOOP_SLOT_END_TYPE()")], 4.5)
    centre = p.add("CENTER_MILLING($,.T.)")
    cp = p.add("CONTOUR_PARALLEL(0.4,.T.,$,.CLIMB.)")
    p.write([("SPLINE GROOVE", s1, bs(p, "FINISH", "SPLINE", ball6, tech, cp, 3.0, None, None, None)),
             ("BEZIER CHANNEL", s2, bs(p, "FINISH", "BEZIER", ball4, tech, centre, None, None, None, None)),
             ("STEPPED SLOT", s3, bs(p, "ROUGH", "STEPPED", mill6, tech, cp, 2.5, None, 0.0, 0.0)),
             ("BEZIER RING", s4, bs(p, "FINISH", "BEZIER RING", ball4, tech, centre, 2.5, None, None, None))])

    p = program("hole-bottoms-blind", "drilling depths checked against blind bottoms: a drill to the lowest point of a spherical bottom and of a flat-with-radius bottom (its point clear of the sphere and of the fillet), a drill through a through hole by its point and the clearance")
    drill8 = p.tool("DRILL 8", "TWIST_DRILL", 8, edge_length=40.0, tip=31.0)
    tech = p.tech(0.01, -20.0)
    sphere = hole(p, 0, 0, 10, 12, "SPHERICAL_HOLE_BOTTOM(" + p.length(5.0) + ")")
    fillet = hole(p, 30, 0, 10, 12, "FLAT_WITH_RADIUS_HOLE_BOTTOM(" + p.length(1.0) + ")")
    through = hole(p, 60, 0, 8, 12)
    p.write([("DRILL TO THE SPHERE", sphere, drill_op(p, "DRILLING", "DRILL SPHERE", drill8, tech, cutting_depth="12.000")),
             ("DRILL TO THE FILLET", fillet, drill_op(p, "DRILLING", "DRILL FILLET", drill8, tech, cutting_depth="12.000")),
             ("DRILL THROUGH", through, drill_op(p, "DRILLING", "DRILL THROUGH", drill8, tech, cutting_depth="15.400"))])

    p = program("hole-bottoms-refused", "drilling depths beyond blind bottoms, each refused naming the limit: below a flat floor, the rim of a reamer into a spherical bottom, a drill below a flat-with-radius floor")
    drill8 = p.tool("DRILL 8", "TWIST_DRILL", 8, edge_length=40.0, tip=31.0)
    reamer = p.tool("REAMER 10", "REAMER", 10, edge_length=30.0)
    tech = p.tech(0.01, -20.0)
    flat = hole(p, 0, 0, 10, 12, "FLAT_HOLE_BOTTOM()")
    sphere = hole(p, 30, 0, 10, 12, "SPHERICAL_HOLE_BOTTOM(" + p.length(5.0) + ")")
    fillet = hole(p, 60, 0, 10, 12, "FLAT_WITH_RADIUS_HOLE_BOTTOM(" + p.length(1.0) + ")")
    p.write([("DRILL BELOW THE FLOOR", flat, drill_op(p, "DRILLING", "DRILL FLAT", drill8, tech, cutting_depth="12.500")),
             ("REAM INTO THE SPHERE", sphere, drill_op(p, "REAMING", "REAM SPHERE", reamer, tech, cutting_depth="12.000", extra=",.F.,$,$")),
             ("DRILL BELOW THE FILLET", fillet, drill_op(p, "DRILLING", "DRILL FILLET", drill8, tech, cutting_depth="12.300"))])

    p = program("slot-section-refused", "general slot sections the generator refuses, each naming the instance: a negative allowance, a Bezier curve whose points do not make whole segments, a dovetail (undercut), an asymmetric section with radiused ends, a ball too large for the groove, a section that does not reach the top, a general section along an arc")
    ball6 = p.tool("BALL 6", "BALL_ENDMILL", 6, edge_length=15.0, edge_radius=3.0)
    ball16 = p.tool("BALL 16", "BALL_ENDMILL", 16, edge_length=20.0, edge_radius=8.0)
    tech = p.tech(0.02, -50.0)
    radiused = p.add("RADIUSED_SLOT_END_TYPE()")
    dovetail = polyline(p, [(-5, 0), (-8, -5), (8, -5), (5, 0)], close=False)
    d = slot_feature(p, "DOVETAIL", 0, 0, line_path(p, 40), p.add(f"GENERAL_PROFILE($,{dovetail})"), [radiused, radiused], 5)
    lopsided = bspline(p, 3, [(-5, 0), (-5, -6), (3, -6), (9, 0)], kind="BEZIER_CURVE")
    a = slot_feature(p, "LOPSIDED RADIUSED", 0, 30, line_path(p, 40), p.add(f"GENERAL_PROFILE($,{lopsided})"), [radiused, radiused], 4.5)
    narrow = bspline(p, 2, [(-3, 0), (0, -8), (3, 0)], kind="QUASI_UNIFORM_CURVE")
    n = slot_feature(p, "NARROW GROOVE", 0, 60, line_path(p, 40), p.add(f"GENERAL_PROFILE($,{narrow})"), [radiused, radiused], 4)
    shallow = bspline(p, 3, [(-8, -1), (-6, -6), (6, -6), (8, -1)])
    sh = slot_feature(p, "SHORT WALLS", 0, 90, line_path(p, 40), p.add(f"GENERAL_PROFILE($,{shallow})"), [radiused, radiused], 5)
    ogee = bspline(p, 3, [(-10, 0), (-8, -4), (-3, -6), (3, -6), (8, -4), (10, 0)])
    arc = p.add(f"PARTIAL_CIRCULAR_PATH($,{p.length(40)},90.0)")
    ar = slot_feature(p, "SPLINE ALONG ARC", 100, 0, arc, p.add(f"GENERAL_PROFILE($,{ogee})"), [radiused, radiused], 5.875)
    broken = bspline(p, 3, [(-8, 0), (-6, -6), (0, -6), (6, -6), (8, 0)], kind="BEZIER_CURVE")
    br = slot_feature(p, "FIVE POINT BEZIER", 0, 120, line_path(p, 40), p.add(f"GENERAL_PROFILE($,{broken})"), [radiused, radiused], 5)
    centre = p.add("CENTER_MILLING($,.T.)")
    og = slot_feature(p, "SPLINE GROOVE", 0, 150, line_path(p, 40), p.add(f"GENERAL_PROFILE($,{ogee})"), [radiused, radiused], 5.875)
    p.write([("NEGATIVE ALLOWANCE", og, bs(p, "ROUGH", "NEGATIVE", ball6, tech, centre, None, None, -0.5, 0.0)),
             ("FIVE POINT BEZIER", br, bs(p, "FINISH", "BEZIER 5", ball6, tech, centre, None, None, None, None)),
             ("DOVETAIL", d, bs(p, "FINISH", "DOVETAIL", ball6, tech, centre, None, None, None, None)),
             ("LOPSIDED RADIUSED", a, bs(p, "FINISH", "LOPSIDED", ball6, tech, centre, None, None, None, None)),
             ("BALL TOO LARGE", n, bs(p, "FINISH", "NARROW", ball16, tech, centre, None, None, None, None)),
             ("SHORT WALLS", sh, bs(p, "FINISH", "SHORT", ball6, tech, centre, None, None, None, None)),
             ("ALONG AN ARC", ar, bs(p, "FINISH", "ARC", ball6, tech, centre, None, None, None, None))])


def interop_geometry_cases():
    p = program("slot-placed-travel", "slots whose course_of_travel has its own placement: a square-U slot along a line placed at (20, 10) turned 30 degrees, a vee slot along a line placed at (0, 60) turned 90 degrees")
    mill10, tech = mill(p, 10, 20), p.tech(0.03, -40.0)
    sink = p.tool("COUNTERSINK 16 X 90", "COUNTERSINK", 16, edge_length=12.0, tip=45.0)
    square = p.add(f"SQUARE_U_PROFILE($,{p.length(16)},{p.length(0)},90.0,{p.length(0)},90.0)")
    radiused = p.add("RADIUSED_SLOT_END_TYPE()")
    u_path = p.add(f"LINEAR_PATH({p.placement(20, 10, 0, ref=rot(30))},{p.length(40)},{p.direction(1, 0, 0)})")
    u_slot = slot_feature(p, "U SLOT PLACED", 0, 0, u_path, square, [radiused, radiused], 6)
    v_path = p.add(f"LINEAR_PATH({p.placement(0, 60, 0, ref=(0, 1, 0))},{p.length(40)},{p.direction(1, 0, 0)})")
    v_slot = slot_feature(p, "VEE SLOT PLACED", 0, 0, v_path, vee_profile(p, 90), [radiused, radiused], 5)
    cp = p.add("CONTOUR_PARALLEL(0.5,.T.,.CCW.,$)")
    centre = p.add("CENTER_MILLING($,.T.)")
    ramp = p.add("PLUNGE_RAMP($,10.0)")
    p.write([("U SLOT", u_slot, bs(p, "ROUGH", "SLOT U", mill10, tech, cp, 3.0, None, 0.0, 0.0, ramp)),
             ("VEE SLOT", v_slot, bs(p, "FINISH", "SLOT VEE", sink, tech, centre, 2.5, None, None, None, ramp))])

    p = program("pocket-placed-profile", "closed pockets whose profile has its own placement: a rectangle moved and turned 45 degrees, a circle moved off the feature origin, an L polyline turned 90 degrees")
    t, tech = mill(p, 8, 20), p.tech(0.03, -40.0)
    prof = p.add(f"RECTANGULAR_CLOSED_PROFILE({p.placement(15, -5, 0, ref=rot(45))},{p.length(24)},{p.length(40)})")
    b = p.add("PLANAR_POCKET_BOTTOM_CONDITION()")
    rect = p.add(f"CLOSED_POCKET('RECT PLACED',#4,(),{p.placement(0, 0, 0)},{p.plane('POCKET DEPTH', -5)},(),$,{b},$,{p.length(5)},{prof})")
    cprof = p.add(f"CIRCULAR_CLOSED_PROFILE({p.placement(30, 0, 0)},{p.length(30)})")
    circle = p.add(f"CLOSED_POCKET('CIRCLE PLACED',#4,(),{p.placement(80, 0, 0)},{p.plane('POCKET DEPTH', -4)},(),$,{b},$,$,{cprof})")
    lpoly = polyline(p, [(0, 0), (40, 0), (40, 15), (15, 15), (15, 30), (0, 30)])
    lprof = p.add(f"GENERAL_CLOSED_PROFILE({p.placement(0, 0, 0, ref=(0, 1, 0))},{lpoly})")
    lpocket = p.add(f"CLOSED_POCKET('L PLACED',#4,(),{p.placement(0, 60, 0)},{p.plane('POCKET DEPTH', -4)},(),$,{b},$,{p.length(5)},{lprof})")
    s = p.add("CONTOUR_PARALLEL(0.5,.T.,.CCW.,$)")
    p.write([("RECT", rect, bs(p, "ROUGH", "RECT", t, tech, s, 2.5, None, 0.0, 0.0)),
             ("CIRCLE", circle, bs(p, "ROUGH", "CIRCLE", t, tech, s, 2.0, None, 0.0, 0.0)),
             ("L", lpocket, bs(p, "FINISH", "L", t, tech, s, 2.0, None, None, None))])

    p = program("hole-milled", "round holes milled rather than drilled: a blind flat hole roughed and finished (helix down, circles round), a through hole, a flat-with-radius bottom with a bull nose, a taper from 20 to 19 in circles down its cone")
    t, tech = mill(p, 10, 30), p.tech(0.03, -40.0)
    bull = p.tool("BULLNOSE 8 R1", "BULLNOSE_ENDMILL", 8, edge_length=25.0, edge_radius=1.0)
    h1 = hole(p, 0, 0, 30, 12, "FLAT_HOLE_BOTTOM()")
    h2 = hole(p, 50, 0, 24, 10)
    h3 = hole(p, 90, 0, 20, 6, "FLAT_WITH_RADIUS_HOLE_BOTTOM(" + p.length(1.0, 0.05) + ")")
    taper = p.add(f"DIAMETER_TAPER({p.length(19, 0.02)})")
    h4 = p.add(f"ROUND_HOLE('TAPER D20-19',#4,(),{p.placement(130, 0, 0)},{p.plane('HOLE DEPTH', -8)},{p.length(20, 0.02)},{taper},{p.add('FLAT_HOLE_BOTTOM()')})")
    cp = p.add("CONTOUR_PARALLEL(0.4,.T.,$,.CLIMB.)")
    hx = p.add("PLUNGE_HELIX($,4.0,5.0)")
    hx2 = p.add("PLUNGE_HELIX($,3.0,5.0)")
    p.write([("HOLE ROUGH", h1, bs(p, "ROUGH", "ROUGH", t, tech, cp, 4.0, None, 0.5, 0.2, hx)),
             ("HOLE FINISH", h1, bs(p, "FINISH", "FINISH", t, tech, cp, 12.0, None, None, None, hx)),
             ("THROUGH HOLE", h2, bs(p, "ROUGH", "THROUGH", t, tech, cp, 5.0, None, 0.0, 0.0, hx)),
             ("RADIUS BOTTOM", h3, bs(p, "FINISH", "RADIUS", bull, tech, cp, 3.0, None, None, None, hx2)),
             ("TAPER", h4, bs(p, "FINISH", "TAPER", bull, tech, cp, 4.0, None, None, None, hx2))])

    p = program("hole-milled-sphere", "round holes with a spherical bottom milled: a cylinder of 30 and a sphere of radius 20 roughed (allowances 0.3) and finished by a ball of 10 (the cylinder helix down, then discs level by level and circles down the sphere within the profile tolerance), a half ball of radius 12 finished from the top by a bull nose whose flat leaves less than the tolerance at its centre")
    tech = p.tech(0.03, -40.0)
    ball10 = p.tool("BALL 10", "BALL_ENDMILL", 10, edge_length=30.0, edge_radius=5.0)
    bull = p.tool("BULLNOSE 8 R3.9", "BULLNOSE_ENDMILL", 8, edge_length=30.0, edge_radius=3.9)
    h1 = hole(p, 0, 0, 30, 16, "SPHERICAL_HOLE_BOTTOM(" + p.length(20.0, 0.05) + ")")
    h2 = hole(p, 60, 0, 24, 12, "SPHERICAL_HOLE_BOTTOM(" + p.length(12.0, 0.05) + ")")
    cp = p.add("CONTOUR_PARALLEL(0.4,.T.,$,.CLIMB.)")
    hx = p.add("PLUNGE_HELIX($,4.0,5.0)")
    p.write([("SPHERE ROUGH", h1, bs(p, "ROUGH", "SPHERE ROUGH", ball10, tech, cp, 4.0, None, 0.3, 0.3, hx)),
             ("SPHERE FINISH", h1, bs(p, "FINISH", "SPHERE FINISH", ball10, tech, cp, 16.0, None, None, None, hx)),
             ("HALF BALL", h2, bs(p, "FINISH", "HALF BALL", bull, tech, cp, 3.0, None, None, None, hx))])

    p = program("hole-milled-sphere-refused", "spherical hole bottoms the generator refuses, naming the tool and the sizes: a flat end mill, a ball larger than the sphere less its allowance, a bull nose whose flat leaves a mound at the centre, a sphere narrower than the hole, side milling (the wall alone) of a spherical bottom")
    tech = p.tech(0.03, -40.0)
    flat = mill(p, 10, 30)
    ball30 = p.tool("BALL 30", "BALL_ENDMILL", 30, edge_length=40.0, edge_radius=15.0)
    bull = p.tool("BULLNOSE 10 R1", "BULLNOSE_ENDMILL", 10, edge_length=30.0, edge_radius=1.0)
    ball6 = p.tool("BALL 6", "BALL_ENDMILL", 6, edge_length=15.0, edge_radius=3.0)
    h1 = hole(p, 0, 0, 30, 16, "SPHERICAL_HOLE_BOTTOM(" + p.length(15.0, 0.05) + ")")
    h2 = hole(p, 60, 0, 30, 16, "SPHERICAL_HOLE_BOTTOM(" + p.length(10.0, 0.05) + ")")
    cp = p.add("CONTOUR_PARALLEL(0.4,.T.,$,.CLIMB.)")
    p.write([("FLAT END", h1, bs(p, "FINISH", "FLAT END", flat, tech, cp, 16.0, None, None, None)),
             ("BALL TOO LARGE", h1, bs(p, "ROUGH", "BALL TOO LARGE", ball30, tech, cp, 4.0, None, 0.0, 0.5)),
             ("BULL NOSE MOUND", h1, bs(p, "FINISH", "BULL NOSE", bull, tech, cp, 16.0, None, None, None)),
             ("SPHERE TOO NARROW", h2, bs(p, "FINISH", "NARROW", ball6, tech, cp, 16.0, None, None, None)),
             ("SIDE MILLING", h1, side_op(p, "FINISH", "SIDE", ball6, tech, cp, 16.0, 0.0))])

    p = program("hole-bottoms-taper", "drilling depths into a conical bottom with a drill whose point is not given; tapered holes (diameter and angle tapers) drilled at their narrowest diameter")
    plain = p.tool("DRILL 10", "TWIST_DRILL", 10, edge_length=40.0)
    drill8 = p.tool("DRILL 8", "TWIST_DRILL", 8, edge_length=40.0, tip=31.0)
    cone = hole(p, 0, 0, 10, 12, "CONICAL_HOLE_BOTTOM(118.0,$)")
    dtaper = p.add(f"DIAMETER_TAPER({p.length(8, 0.02)})")
    ataper = p.add("ANGLE_TAPER(2.862405226)")  # tan = 1/20: from 10 to 8 over the depth 20
    b1 = p.add("THROUGH_BOTTOM_CONDITION()")
    t1 = p.add(f"ROUND_HOLE('TAPER D10-8',#4,(),{p.placement(30, 0, 0)},{p.plane('HOLE DEPTH', -15)},{p.length(10, 0.02)},{dtaper},{b1})")
    t2 = p.add(f"ROUND_HOLE('TAPER 2 DEG',#4,(),{p.placement(60, 0, 0)},{p.plane('HOLE DEPTH', -20)},{p.length(10, 0.02)},{ataper},{b1})")
    tech = p.tech(0.01, -20.0)
    p.write([("DRILL INTO CONE", cone, drill_op(p, "DRILLING", "DRILL CONE", plain, tech, cutting_depth="14.800")),
             ("DRILL DIAMETER TAPER", t1, drill_op(p, "DRILLING", "DRILL TAPER", drill8, tech)),
             ("DRILL ANGLE TAPER", t2, drill_op(p, "DRILLING", "DRILL ANGLE", drill8, tech))])

    p = program("pocket-rough-corners", "roughing passes whose tool radius + side allowance exceed the corner radius (a warning with the stock left), finished by a tool that fits")
    big, small, tech = mill(p, 16, 20), mill(p, 8, 20), p.tech(0.03, -40.0)
    rect = rect_pocket(p, 0, 0, 60, 40, 6, 5)
    lpoly = polyline(p, [(0, 0), (60, 0), (60, 25), (25, 25), (25, 45), (0, 45)])
    lpocket = general_pocket(p, "L POCKET", 80, 0, lpoly, 5, corner=4)
    cp = p.add("CONTOUR_PARALLEL(0.5,.T.,.CCW.,$)")
    p.write([("RECT ROUGH", rect, bs(p, "ROUGH", "RECT ROUGH", big, tech, cp, 3.0, None, 0.5, 0.0)),
             ("RECT FINISH", rect, bs(p, "FINISH", "RECT FINISH", small, tech, cp, 6.0, None, None, None)),
             ("L ROUGH", lpocket, bs(p, "ROUGH", "L ROUGH", big, tech, cp, 2.5, None, 0.5, 0.0)),
             ("L FINISH", lpocket, bs(p, "FINISH", "L FINISH", small, tech, cp, 5.0, None, None, None))])

    p = program("geometry-refused", "geometry the generator refuses, each naming the instance: a milled taper that widens downwards, a drill wider than a taper, a cutting depth past the point of a cone, a course of travel placed out of the slot plane, free-form region milling")
    t, tech = mill(p, 10, 30), p.tech(0.03, -40.0)
    drill10 = p.tool("DRILL 10", "TWIST_DRILL", 10, edge_length=40.0)
    dtaper = p.add(f"DIAMETER_TAPER({p.length(8, 0.02)})")
    b1 = p.add("FLAT_HOLE_BOTTOM()")
    wider = p.add(f"DIAMETER_TAPER({p.length(36, 0.02)})")
    taper = p.add(f"ROUND_HOLE('UNDERCUT TAPER',#4,(),{p.placement(0, 0, 0)},{p.plane('HOLE DEPTH', -15)},{p.length(30, 0.02)},{wider},{b1})")
    taper10 = p.add(f"ROUND_HOLE('TAPER D10-8',#4,(),{p.placement(40, 0, 0)},{p.plane('HOLE DEPTH', -15)},{p.length(10, 0.02)},{dtaper},{b1})")
    cone = hole(p, 60, 0, 10, 12, "CONICAL_HOLE_BOTTOM(118.0,$)")
    square = p.add(f"SQUARE_U_PROFILE($,{p.length(16)},{p.length(0)},90.0,{p.length(0)},90.0)")
    radiused = p.add("RADIUSED_SLOT_END_TYPE()")
    tilted = p.add(f"LINEAR_PATH({p.placement(0, 0, 0, axis=(0, 1, 0), ref=(1, 0, 0))},{p.length(40)},{p.direction(1, 0, 0)})")
    tslot = slot_feature(p, "SLOT TILTED TRAVEL", 0, 40, tilted, square, [radiused, radiused], 5)
    cps = [[p.point(x, y, z) for x, y, z in row] for row in
           [[(0, 0, 0), (0, 20, 1), (0, 40, 0)], [(20, 0, 1), (20, 20, 3), (20, 40, 1)], [(40, 0, 0), (40, 20, 1), (40, 40, 0)]]]
    grid = ",".join("(" + ",".join(r) + ")" for r in cps)
    surface = p.add(f"BEZIER_SURFACE('',2,2,({grid}),.UNSPECIFIED.,.F.,.F.,.F.)")
    region = p.add(f"REGION_SURFACE_LIST('FREEFORM REGION',#4,(),{p.placement(100, 0, 0)},({surface}))")
    cp = p.add("CONTOUR_PARALLEL(0.4,.T.,$,.CLIMB.)")
    ff = p.add(f"FREEFORM_OPERATION($,$,'FREEFORM',5.000,$,{t},{tech},{p.functions()},$,$,$,$)")
    p.write([("MILL TAPER", taper, bs(p, "ROUGH", "TAPER", t, tech, cp, 4.0, None, 0.0, 0.0)),
             ("DRILL TOO WIDE FOR TAPER", taper10, drill_op(p, "DRILLING", "DRILL WIDE", drill10, p.tech(0.01, -20.0))),
             ("DRILL PAST CONE", cone, drill_op(p, "DRILLING", "DRILL DEEP", drill10, p.tech(0.01, -20.0), cutting_depth="15.500")),
             ("SLOT TILTED", tslot, bs(p, "ROUGH", "TILTED", t, tech, cp, 3.0, None, 0.0, 0.0)),
             ("FREEFORM", region, ff)])

    section_cases()

    # Every kind above in one program, as a CAPP system writes a part: a ring groove along a
    # circular path placed off the feature origin and turned, a pocket with a placed profile
    # roughed into its corners then finished, a milled hole, a drilling depth into a cone, a
    # tapered hole drilled at its narrowest diameter.
    p = program("geometry-combined", "issue 17 geometry in one part: placed circular course of travel, placed pocket profile roughed into tight corners and finished, milled hole, drilling into a cone, tapered hole, a half-ball hole bottom milled")
    big, small, tech = mill(p, 16, 25), mill(p, 8, 20), p.tech(0.03, -40.0)
    ball6 = p.tool("BALL 6", "BALL_ENDMILL", 6, edge_length=15.0, edge_radius=3.0)
    drill = p.tool("DRILL 10", "TWIST_DRILL", 10, edge_length=40.0)
    drill8 = p.tool("DRILL 8", "TWIST_DRILL", 8, edge_length=40.0, tip=31.0)
    loop = p.add("LOOP_SLOT_END_TYPE()")
    ring = p.add(f"COMPLETE_CIRCULAR_PATH({p.placement(20, 0, 0, ref=rot(60))},{p.length(25)})")
    groove = slot_feature(p, "RING GROOVE", 0, 0, ring, p.add(f"ROUNDED_U_PROFILE($,{p.length(6)})"), [loop], 3)
    prof = p.add(f"RECTANGULAR_CLOSED_PROFILE({p.placement(10, 5, 0, ref=rot(-20))},{p.length(36)},{p.length(56)})")
    b = p.add("PLANAR_POCKET_BOTTOM_CONDITION()")
    pocket = p.add(f"CLOSED_POCKET('POCKET',#4,(),{p.placement(100, 0, 0)},{p.plane('POCKET DEPTH', -6)},(),$,{b},$,{p.length(5)},{prof})")
    milled = hole(p, 0, 80, 26, 10, "FLAT_HOLE_BOTTOM()")
    cone = hole(p, 50, 80, 10, 12, "CONICAL_HOLE_BOTTOM(118.0,$)")
    dtaper = p.add(f"DIAMETER_TAPER({p.length(8, 0.02)})")
    through = p.add("THROUGH_BOTTOM_CONDITION()")
    taper = p.add(f"ROUND_HOLE('TAPER D10-8',#4,(),{p.placement(80, 80, 0)},{p.plane('HOLE DEPTH', -15)},{p.length(10, 0.02)},{dtaper},{through})")
    cp = p.add("CONTOUR_PARALLEL(0.5,.T.,.CCW.,$)")
    centre = p.add("CENTER_MILLING($,.T.)")
    ramp = p.add("PLUNGE_RAMP($,5.0)")
    hx = p.add("PLUNGE_HELIX($,4.0,5.0)")
    dtech = p.tech(0.01, -20.0)
    p.write([("RING GROOVE", groove, bs(p, "FINISH", "GROOVE", ball6, tech, centre, 1.5, None, None, None, ramp)),
             ("POCKET ROUGH", pocket, bs(p, "ROUGH", "POCKET ROUGH", big, tech, cp, 3.0, None, 0.5, 0.0)),
             ("POCKET FINISH", pocket, bs(p, "FINISH", "POCKET FINISH", small, tech, cp, 6.0, None, None, None)),
             ("MILLED HOLE", milled, bs(p, "ROUGH", "HOLE", small, tech, cp, 5.0, None, 0.0, 0.0, hx)),
             ("DRILL INTO CONE", cone, drill_op(p, "DRILLING", "DRILL CONE", drill, dtech, cutting_depth="14.800")),
             ("DRILL TAPER", taper, drill_op(p, "DRILLING", "DRILL TAPER", drill8, dtech)),
             ("HALF BALL HOLE", hole(p, 120, 80, 16, 10, "SPHERICAL_HOLE_BOTTOM(" + p.length(8.0, 0.05) + ")"),
              bs(p, "FINISH", "HALF BALL", ball6, tech, cp, 5.0, None, None, None, hx))])


if __name__ == "__main__":
    main()
    general_cases()
    interop_geometry_cases()
