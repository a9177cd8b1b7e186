#!/usr/bin/env python3
"""Writes the verifier's golden programs (cases/*.stp): one good part, and variants that each
break one rule by a known amount at a known place. Run it after changing a case; the .stp files
are committed, so the tests do not need Python.

The part (workpiece coordinates = machine coordinates; setup and workpiece set-up at the origin):
  stock BLOCK x 0..100, y 0..80, z -30..2; security plane z 20
  FACE1    PLANAR_FACE at z 2, depth 2 (floor z 0), 100 (x) by 80 (y); face mill D50
  POCKET1  CLOSED_POCKET at (50, 40, 0), 40 (x) by 30 (y), corner radius 6, floor z -10;
           end mill D10, BOTTOM_AND_SIDE_FINISH_MILLING, approach PLUNGE_RAMP 15 deg
  HOLE1    ROUND_HOLE at (20, 20, 0), diameter 10, flat bottom at z -15; twist drill D10
"""

import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


class P21:
    def __init__(self):
        self.lines = []
        self.next = 1000

    def add(self, text, ident=None):
        if ident is None:
            ident = self.next
            self.next += 1
        self.lines.append(f"#{ident}={text};")
        return f"#{ident}"

    def point(self, p):
        return self.add("CARTESIAN_POINT('',(%s))" % ",".join(f"{c:.4f}" for c in p))

    def polyline(self, name, points, kind=".TRAJECTORY_PATH."):
        pts = ",".join(self.point(p) for p in points)
        curve = self.add(f"POLYLINE('{name}',({pts}))")
        return self.add(f"CUTTER_LOCATION_TRAJECTORY(.T.,{kind},$,$,$,$,{curve},$,$)")

    def toolpaths(self, paths):
        return self.add("TOOLPATH_LIST((%s))" % ",".join(paths))


def arc_points(cx, cy, r, a0, a1, n, z):
    return [(cx + r * math.cos(math.radians(a0 + (a1 - a0) * k / n)),
             cy + r * math.sin(math.radians(a0 + (a1 - a0) * k / n)), z) for k in range(n + 1)]


def pocket_rings(z, rings=(2, 1, 0), wall_shift=0.0):
    """The pocket's finishing level in its own frame: rectangular rings from the inside out, the
    outermost with 1 mm corner arcs so that the tool (r 5) just touches the 6 mm corners."""
    pts = [(-12.0, 0.0, z)]
    half = {2: (7.0, 2.0), 1: (11.0, 6.0)}
    for ring in rings:
        if ring in half:
            hx, hy = half[ring]
            pts += [(-hx, 0, z), (-hx, -hy, z), (hx, -hy, z), (hx, hy, z), (-hx, hy, z),
                    (-hx, 0, z)]
        else:
            # Outer ring: centre path |x| <= 15, |y| <= 10, corners arcs of radius 1 about
            # (+-14, +-9); `wall_shift` pushes the +x side into the wall.
            e = 15.0 + wall_shift
            pts += [(-15, 0, z), (-15, -9, z)]
            pts += arc_points(-14, -9, 1, 180, 270, 8, z)[1:]
            pts += [(14, -10, z)]
            pts += [(p[0] + (wall_shift if p[0] > 14 else 0), p[1], z)
                    for p in arc_points(14, -9, 1, 270, 360, 8, z)[1:]]
            pts += [(e, -9, z), (e, 9, z)]
            pts += [(p[0] + (wall_shift if p[0] > 14 else 0), p[1], z)
                    for p in arc_points(14, 9, 1, 0, 90, 8, z)[1:]]
            pts += [(-14, 10, z)]
            pts += arc_points(-14, 9, 1, 90, 180, 8, z)[1:]
            pts += [(-15, 0, z)]
    return pts


def program(name, description, pocket_path=None, pocket_approach="ramp", floor_z=-10.0,
            extra_rapid=None, hole_depth=-15.0, step=False, slot=False):
    f = P21()
    # ---- structure ----
    elements = ["#10", "#11", "#12"]
    if extra_rapid:
        elements.append("#13")
    f.add("PROJECT('%s',#2,(#900),$,$,$)" % name.upper(), 1)
    f.add("WORKPLAN('MAIN',(%s),$,#8,$)" % ",".join(elements), 2)
    f.add("SETUP('SETUP1',#923,#910,(#9))", 8)
    f.add("WORKPIECE_SETUP(#900,#923,$,$,())", 9)
    f.add("MACHINING_WORKINGSTEP('WS FACE',#910,#20,#30,$)", 10)
    f.add("MACHINING_WORKINGSTEP('WS POCKET',#910,#21,#31,$)", 11)
    f.add("MACHINING_WORKINGSTEP('WS DRILL',#910,#22,#32,$)", 12)
    # ---- features ----
    f.add("PLANAR_FACE('FACE1',#900,(#30),#940,#941,#942,#944,$,())", 20)
    if slot:
        # POCKET1's outline as a straight SLOT: from (30, 40) 40 along x, square-U 30 wide,
        # flat ends with 6 mm corners. Its frame starts 20 mm before the pocket's centre.
        f.add("SLOT('SLOT1',#900,(#31),#970,#951,#967,#968,(#969))", 21)
        f.add("LINEAR_PATH($,#959,#922)", 967)
        f.add("SQUARE_U_PROFILE($,#958,#971,90.,#971,90.)", 968)
        f.add("FLAT_SLOT_END_TYPE(#953,#953)", 969)
        f.add("AXIS2_PLACEMENT_3D('SLOT1',#972,#921,#922)", 970)
        f.add("TOLERANCED_LENGTH_MEASURE(0.,#925)", 971)
        f.add("CARTESIAN_POINT('',(30.,40.,0.))", 972)
    elif step:
        # POCKET1 declared as a SPHERICAL_CAP: a kind the verifier does not check, which it must
        # say.
        f.add("SPHERICAL_CAP('CAP1',#900,(#31),#950,#951,#967,#968)", 21)
        f.add("NUMERIC_PARAMETER('INTERNAL ANGLE',90.,'DEG')", 967)
        f.add("NUMERIC_PARAMETER('RADIUS',20.,'MM')", 968)
    else:
        f.add("CLOSED_POCKET('POCKET1',#900,(#31),#950,#951,(),$,#952,$,#953,#954)", 21)
    f.add("ROUND_HOLE('HOLE1',#900,(#32),#960,#961,#962,$,#963)", 22)
    # ---- operations ----
    f.add("PLANE_FINISH_MILLING(#300,$,'FACE OP',10.,$,#70,#80,#90,$,#60,$,#62,2.,0.)", 30)
    approach = {"ramp": "#61", "helix": "#63", "none": "$"}[pocket_approach]
    f.add("BOTTOM_AND_SIDE_FINISH_MILLING(#310,$,'POCKET OP',10.,$,#71,#81,#90,$,%s,$,#64,"
          "10.,4.,0.,0.)" % approach, 31)
    f.add("DRILLING(#320,$,'DRILL OP',10.,$,#72,#82,#90,$,$,$,$,$,$)", 32)
    f.add("PLUNGE_TOOLAXIS($)", 60)
    f.add("PLUNGE_RAMP($,15.)", 61)
    f.add("BIDIRECTIONAL_MILLING($,.T.,#922,.LEFT.,$)", 62)
    f.add("PLUNGE_HELIX($,3.,5.)", 63)
    f.add("CONTOUR_PARALLEL($,.T.,.CCW.,.CLIMB.)", 64)
    # ---- tools and technology ----
    f.add("MILLING_CUTTING_TOOL('FACE MILL 50',#700,(#79),80.,$,$)", 70)
    f.add("FACEMILL(#701,5,.RIGHT.,.F.,$)", 700)
    f.add("MILLING_TOOL_DIMENSION(50.,$,$,10.,$,$,$)", 701)
    f.add("MILLING_CUTTING_TOOL('END MILL 10',#710,(#79),70.,$,$)", 71)
    f.add("ENDMILL(#711,3,.RIGHT.,.F.,$)", 710)
    f.add("MILLING_TOOL_DIMENSION(10.,$,$,25.,0.,$,$)", 711)
    f.add("MILLING_CUTTING_TOOL('DRILL 10',#720,(#79),90.,$,$)", 72)
    f.add("TWIST_DRILL(#721,2,.RIGHT.,.F.,$)", 720)
    f.add("MILLING_TOOL_DIMENSION(10.,59.,$,40.,$,$,$)", 721)
    f.add("CUTTING_COMPONENT(70.,$,$,$,$)", 79)
    f.add("MILLING_TECHNOLOGY(0.02,.TCP.,$,-20.,$,.F.,.F.,.F.,$)", 80)
    f.add("MILLING_TECHNOLOGY(0.01,.TCP.,$,-50.,$,.F.,.F.,.F.,$)", 81)
    f.add("MILLING_TECHNOLOGY(0.005,.TCP.,$,-30.,$,.F.,.F.,.F.,$)", 82)
    f.add("MILLING_MACHINE_FUNCTIONS(.T.,$,$,.F.,$,(),.F.,$,$,())", 90)
    # ---- workpiece, planes, placements ----
    f.add("WORKPIECE('PART',$,$,$,$,#901,())", 900)
    f.add("BLOCK('STOCK',#902,100.,80.,32.)", 901)
    f.add("AXIS2_PLACEMENT_3D('STOCK CORNER',#903,#921,#922)", 902)
    f.add("CARTESIAN_POINT('',(0.,0.,-30.))", 903)
    f.add("PLANE('SECURITY PLANE',#911)", 910)
    f.add("AXIS2_PLACEMENT_3D('SECURITY',#912,#921,#922)", 911)
    f.add("CARTESIAN_POINT('',(0.,0.,20.))", 912)
    f.add("CARTESIAN_POINT('ORIGIN',(0.,0.,0.))", 920)
    f.add("DIRECTION('Z',(0.,0.,1.))", 921)
    f.add("DIRECTION('X',(1.,0.,0.))", 922)
    f.add("AXIS2_PLACEMENT_3D('IDENTITY',#920,#921,#922)", 923)
    f.add("DIRECTION('Y',(0.,1.,0.))", 924)
    f.add("PLUS_MINUS_VALUE(0.05,0.05,2)", 925)
    # face: placed at z 2, depth plane 2 below, 80 along y by 100 along x
    f.add("AXIS2_PLACEMENT_3D('FACE1',#945,#921,#922)", 940)
    f.add("PLANE('FACE1 DEPTH',#946)", 941)
    f.add("LINEAR_PATH($,#943,#924)", 942)
    f.add("TOLERANCED_LENGTH_MEASURE(80.,#925)", 943)
    f.add("LINEAR_PROFILE($,#947)", 944)
    f.add("CARTESIAN_POINT('',(0.,0.,2.))", 945)
    f.add("AXIS2_PLACEMENT_3D('FACE1 DEPTH',#948,#921,#922)", 946)
    f.add("NUMERIC_PARAMETER('WIDTH',100.,'MM')", 947)
    f.add("CARTESIAN_POINT('',(0.,0.,-2.))", 948)
    # pocket
    f.add("AXIS2_PLACEMENT_3D('POCKET1',#955,#921,#922)", 950)
    f.add("PLANE('POCKET1 DEPTH',#956)", 951)
    f.add("PLANAR_POCKET_BOTTOM_CONDITION()", 952)
    f.add("TOLERANCED_LENGTH_MEASURE(6.,#925)", 953)
    f.add("RECTANGULAR_CLOSED_PROFILE($,#958,#959)", 954)
    f.add("CARTESIAN_POINT('',(50.,40.,0.))", 955)
    f.add("AXIS2_PLACEMENT_3D('POCKET1 DEPTH',#957,#921,#922)", 956)
    f.add("CARTESIAN_POINT('',(0.,0.,-10.))", 957)
    f.add("TOLERANCED_LENGTH_MEASURE(30.,#925)", 958)
    f.add("TOLERANCED_LENGTH_MEASURE(40.,#925)", 959)
    # hole
    f.add("AXIS2_PLACEMENT_3D('HOLE1',#964,#921,#922)", 960)
    f.add("PLANE('HOLE1 DEPTH',#965)", 961)
    f.add("TOLERANCED_LENGTH_MEASURE(10.,#925)", 962)
    f.add("FLAT_HOLE_BOTTOM()", 963)
    f.add("CARTESIAN_POINT('',(20.,20.,0.))", 964)
    f.add("AXIS2_PLACEMENT_3D('HOLE1 DEPTH',#966,#921,#922)", 965)
    f.add("CARTESIAN_POINT('',(0.,0.,-15.))", 966)
    # ---- toolpaths (each in its feature's frame) ----
    # Face: three passes along y at x 10, 50, 90 (stepover 40 < 50) at the face's depth (local
    # z -2), entering and leaving outside the stock.
    face = [(10, -30, 5), (10, -30, -2), (10, 110, -2), (50, 110, -2), (50, -30, -2),
            (90, -30, -2), (90, 110, -2), (90, 110, 5)]
    f.add("TOOLPATH_LIST((%s))" % f.polyline("FACE PASSES", face), 300)
    # Pocket: ramp at 14 deg (< 15) to the floor, then the finishing rings.
    if pocket_path is None:
        ramp = [(-12.0, 0.0, 2.0), (12.0, 0.0, -4.0), (-12.0, 0.0, floor_z)]
        pocket_path = ramp + pocket_rings(floor_z)[1:] + [(-15.0, 0.0, 2.0)]
    if slot:
        pocket_path = [(p[0] + 20.0, p[1], p[2]) for p in pocket_path]
    f.add("TOOLPATH_LIST((%s))" % f.polyline("POCKET", pocket_path), 310)
    hole = [(0, 0, 5), (0, 0, hole_depth), (0, 0, 5)]
    f.add("TOOLPATH_LIST((%s))" % f.polyline("DRILL", hole), 320)
    if extra_rapid:
        f.add("RAPID_MOVEMENT('RAPID ACROSS',#910,#330,$)", 13)
        f.add("TOOLPATH_LIST((%s))" % f.polyline("RAPID", extra_rapid, ".NON_CONTACT."), 330)

    def key(line):
        return int(line[1:line.index("=")])

    text = ["ISO-10303-21;", "HEADER;",
            "FILE_DESCRIPTION(('ncpost verify case: %s'),'2;1');" % description.replace("'", "''"),
            "FILE_NAME('%s.stp','2026-11-22T00:00:00',('ncpost'),('ncpost project'),'',"
            "'tests/golden/verify/make_cases.py','');" % name,
            "FILE_SCHEMA(('MACHINING_SCHEMA','MILLING_SCHEMA'));", "ENDSEC;", "DATA;"]
    text += sorted(f.lines, key=key)
    text += ["ENDSEC;", "END-ISO-10303-21;", ""]
    with open(os.path.join(HERE, "cases", name + ".stp"), "w") as out:
        out.write("\n".join(text))


def shape_program(name, description, feature, tool, path, approach="$"):
    """One profiled feature (a slot of another profile, a step) machined by one explicit path
    (in the feature's frame), in a block x 0..100, y 0..80, z -30..0; security plane z 20.
    `feature(f)` adds the feature as #21 (its operations #31) with its own instances from #950,
    `tool` is the body and dimension text of the tool #71."""
    f = P21()
    f.add("PROJECT('%s',#2,(#900),$,$,$)" % name.upper(), 1)
    f.add("WORKPLAN('MAIN',(#11),$,#8,$)", 2)
    f.add("SETUP('SETUP1',#923,#910,(#9))", 8)
    f.add("WORKPIECE_SETUP(#900,#923,$,$,())", 9)
    f.add("MACHINING_WORKINGSTEP('WS CUT',#910,#21,#31,$)", 11)
    feature(f)
    f.add("BOTTOM_AND_SIDE_FINISH_MILLING(#310,$,'CUT',10.,$,#71,#81,#90,$,%s,$,$,$,$,0.,0.)"
          % approach, 31)
    f.add("MILLING_CUTTING_TOOL('TOOL',#710,(#79),70.,$,$)", 71)
    body, dimension = tool
    f.add(body, 710)
    f.add(dimension, 711)
    f.add("CUTTING_COMPONENT(70.,$,$,$,$)", 79)
    f.add("MILLING_TECHNOLOGY(0.01,.TCP.,$,-50.,$,.F.,.F.,.F.,$)", 81)
    f.add("MILLING_MACHINE_FUNCTIONS(.T.,$,$,.F.,$,(),.F.,$,$,())", 90)
    f.add("WORKPIECE('PART',$,$,$,$,#901,())", 900)
    f.add("BLOCK('STOCK',#902,100.,80.,30.)", 901)
    f.add("AXIS2_PLACEMENT_3D('STOCK CORNER',#903,#921,#922)", 902)
    f.add("CARTESIAN_POINT('',(0.,0.,-30.))", 903)
    f.add("PLANE('SECURITY PLANE',#911)", 910)
    f.add("AXIS2_PLACEMENT_3D('SECURITY',#912,#921,#922)", 911)
    f.add("CARTESIAN_POINT('',(0.,0.,20.))", 912)
    f.add("CARTESIAN_POINT('ORIGIN',(0.,0.,0.))", 920)
    f.add("DIRECTION('Z',(0.,0.,1.))", 921)
    f.add("DIRECTION('X',(1.,0.,0.))", 922)
    f.add("AXIS2_PLACEMENT_3D('IDENTITY',#920,#921,#922)", 923)
    f.add("DIRECTION('Y',(0.,1.,0.))", 924)
    f.add("PLUS_MINUS_VALUE(0.05,0.05,2)", 925)
    f.add("TOOLPATH_LIST((%s))" % f.polyline("CUT", path), 310)

    def key(line):
        return int(line[1:line.index("=")])

    text = ["ISO-10303-21;", "HEADER;",
            "FILE_DESCRIPTION(('ncpost verify case: %s'),'2;1');" % description.replace("'", "''"),
            "FILE_NAME('%s.stp','2026-11-22T00:00:00',('ncpost'),('ncpost project'),'',"
            "'tests/golden/verify/make_cases.py','');" % name,
            "FILE_SCHEMA(('MACHINING_SCHEMA','MILLING_SCHEMA'));", "ENDSEC;", "DATA;"]
    text += sorted(f.lines, key=key)
    text += ["ENDSEC;", "END-ISO-10303-21;", ""]
    with open(os.path.join(HERE, "cases", name + ".stp"), "w") as out:
        out.write("\n".join(text))


def slot_feature(profile, ends, depth, length=40.0, x=20.0, y=40.0):
    """A SLOT at (x, y) along +x, `profile` and `ends` the texts of #968 and of its end types
    (#969, #970)."""
    def add(f):
        items = ",".join(f"#{969 + k}" for k in range(len(ends)))
        f.add(f"SLOT('SLOT1',#900,(#31),#950,#951,#967,#968,({items}))", 21)
        f.add("AXIS2_PLACEMENT_3D('SLOT1',#955,#921,#922)", 950)
        f.add("PLANE('SLOT1 DEPTH',#956)", 951)
        f.add(f"CARTESIAN_POINT('',({x:.1f},{y:.1f},0.))", 955)
        f.add("AXIS2_PLACEMENT_3D('SLOT1 DEPTH',#957,#921,#922)", 956)
        f.add(f"CARTESIAN_POINT('',(0.,0.,{-depth:.1f}))", 957)
        f.add("LINEAR_PATH($,#959,#922)", 967)
        f.add(f"TOLERANCED_LENGTH_MEASURE({length:.1f},#925)", 959)
        f.add(profile, 968)
        for k, e in enumerate(ends):
            f.add(e, 969 + k)
        f.add("TOLERANCED_LENGTH_MEASURE(0.,#925)", 971)
        f.add("TOLERANCED_LENGTH_MEASURE(8.,#925)", 972)
        f.add("TOLERANCED_LENGTH_MEASURE(20.,#925)", 973)
        f.add("TOLERANCED_LENGTH_MEASURE(6.,#925)", 974)
    return add


def step_feature(f):
    """A STEP along y at x 0 (its open boundary), the foot of its wall at x 25, 8 deep."""
    f.add("STEP('STEP1',#900,(#31),#950,#951,#967,#968,())", 21)
    f.add("AXIS2_PLACEMENT_3D('STEP1',#920,#921,#922)", 950)
    f.add("PLANE('STEP1 DEPTH',#956)", 951)
    f.add("AXIS2_PLACEMENT_3D('STEP1 DEPTH',#957,#921,#922)", 956)
    f.add("CARTESIAN_POINT('',(0.,0.,-8.))", 957)
    f.add("LINEAR_PATH($,#959,#924)", 967)
    f.add("TOLERANCED_LENGTH_MEASURE(80.,#925)", 959)
    f.add("VEE_PROFILE(#958,#971,90.,0.)", 968)
    f.add("AXIS2_PLACEMENT_3D('WALL FOOT',#960,#921,#922)", 958)
    f.add("CARTESIAN_POINT('',(25.,0.,-8.))", 960)
    f.add("TOLERANCED_LENGTH_MEASURE(0.,#925)", 971)


def woodruff_arc(length, depth, woodruff, ball, end, z_from=None):
    """The ball's tip along a woodruff end's arc, from the bottom out of the slot (end 1, at
    x = length) or into it (end 0, at x = 0), 0.5 degree apart."""
    axis = -depth + woodruff
    rho = woodruff - ball
    pts = []
    phi = 0.0
    while True:
        x = rho * math.sin(math.radians(phi))
        z = axis - rho * math.cos(math.radians(phi)) - ball
        pts.append((length + x if end == 1 else -x, 0.0, z))
        if z >= 0 or phi >= 90:
            break
        phi += 0.5
    return pts if end == 1 else list(reversed(pts))


def shape_cases():
    countersink = ("COUNTERSINK(#711,4,.RIGHT.,.F.,$,$)",
                   "MILLING_TOOL_DIMENSION(16.,45.,$,12.,0.,$,$)")
    ball8 = ("BALL_ENDMILL(#711,2,.RIGHT.,.F.,$)", "MILLING_TOOL_DIMENSION(8.,$,$,16.,4.,$,$)")
    ball12 = ("BALL_ENDMILL(#711,2,.RIGHT.,.F.,$)", "MILLING_TOOL_DIMENSION(12.,$,$,20.,6.,$,$)")
    endmill10 = ("ENDMILL(#711,3,.RIGHT.,.F.,$)", "MILLING_TOOL_DIMENSION(10.,$,$,25.,0.,$,$)")
    radiused = "RADIUSED_SLOT_END_TYPE()"
    # A 90-degree vee 5 deep along x, radiused ends: the countersink's point on its bottom.
    vee = slot_feature("VEE_PROFILE($,#971,90.,45.)", [radiused, radiused], 5)
    shape_program("vee-good", "a 90-degree vee slot cut by a countersink of its angle", vee,
                  countersink, [(0, 0, 5), (0, 0, -5), (40, 0, -5), (40, 0, 5)])
    # The same path 0.3 mm deeper: the cone cuts 0.3 sin 45 = 0.21 into both walls.
    shape_program("vee-too-deep", "the countersink 0.3 mm too deep in the vee", vee, countersink,
                  [(0, 0, 5), (0, 0, -5.3), (40, 0, -5.3), (40, 0, 5)])
    # 1 mm short: the bottom is not reached, and the vee's walls are left 0.7 mm thick.
    shape_program("vee-shallow", "the countersink 1 mm short of the vee's bottom", vee,
                  countersink, [(0, 0, 5), (0, 0, -4), (40, 0, -4), (40, 0, 5)])
    # A rounded-U keyway 8 wide, 5 deep, woodruff ends of radius 20: the ball along the arcs.
    keyway = slot_feature("ROUNDED_U_PROFILE($,#972)",
                          ["WOODRUFF_SLOT_END_TYPE(#973)", "WOODRUFF_SLOT_END_TYPE(#973)"], 5,
                          length=30.0)
    arcs = woodruff_arc(30, 5, 20, 4, 0) + woodruff_arc(30, 5, 20, 4, 1)
    shape_program("woodruff-good", "a keyway with woodruff ends, the ball rising along their arcs",
                  keyway, ball8, [(arcs[0][0], 0, 5)] + arcs + [(arcs[-1][0], 0, 5)])
    # The ball runs on 3 mm past the end of the course of travel at the bottom.
    shape_program("woodruff-overcut", "the ball runs 3 mm along the bottom past a woodruff end",
                  keyway, ball8, [(arcs[0][0], 0, 5)] + arcs[:arcs.index((0.0, 0.0, -5.0)) + 1] +
                  [(33.0, 0, -5.0), (33.0, 0, 5)])
    # A partial-circular slot (radius 6, 120 degrees, 3 deep): a ball 12 along the centre, then
    # 0.5 mm to the side, into the arc.
    arc = slot_feature("PARTIAL_CIRCULAR_PROFILE($,#974,120.)", [radiused, radiused], 3)
    shape_program("partial-circle-off-centre", "a ball of the profile's radius 0.5 mm off the centre",
                  arc, ball12, [(0, 0, 5), (0, 0, -3), (40, 0, -3), (40, 0.5, -3), (0, 0.5, -3),
                                (0, 0.5, 5)])
    # A step 25 wide: passes along y, the last one 0.4 mm into the wall at x 25.
    passes = [(-7, -7, 5), (-7, -7, -8)]
    for k, x in enumerate((3.0, 11.0, 20.4)):
        y0, y1 = (-7, 87) if k % 2 == 0 else (87, -7)
        passes += [(x, y0, -8), (x, y1, -8)]
    passes.append((20.4, 87, 5))
    shape_program("step-wall-gouge", "the last pass over a step 0.4 mm into its wall", step_feature,
                  endmill10, passes)
    good = [(p[0] if p[0] != 20.4 else 20.0, p[1], p[2]) for p in passes]
    shape_program("step-good", "a step cut to its wall", step_feature, endmill10, good)


def placed_slot_feature(f):
    """A square-U SLOT 10 wide, 5 deep, radiused ends, at (20, 40), whose LINEAR_PATH (40 along
    its x) has its own placement: at (0, 10) of the feature, turned 90 degrees (issue 17). Its
    centre line runs from (20, 50) to (20, 90)."""
    f.add("SLOT('SLOT1',#900,(#31),#950,#951,#967,#968,(#969,#970))", 21)
    f.add("AXIS2_PLACEMENT_3D('SLOT1',#955,#921,#922)", 950)
    f.add("PLANE('SLOT1 DEPTH',#956)", 951)
    f.add("CARTESIAN_POINT('',(20.,40.,0.))", 955)
    f.add("AXIS2_PLACEMENT_3D('SLOT1 DEPTH',#957,#921,#922)", 956)
    f.add("CARTESIAN_POINT('',(0.,0.,-5.))", 957)
    f.add("LINEAR_PATH(#961,#959,#922)", 967)
    f.add("AXIS2_PLACEMENT_3D('TRAVEL',#962,#921,#924)", 961)
    f.add("CARTESIAN_POINT('',(0.,10.,0.))", 962)
    f.add("TOLERANCED_LENGTH_MEASURE(40.,#925)", 959)
    f.add("SQUARE_U_PROFILE($,#975,#971,90.,#971,90.)", 968)
    f.add("RADIUSED_SLOT_END_TYPE()", 969)
    f.add("RADIUSED_SLOT_END_TYPE()", 970)
    f.add("TOLERANCED_LENGTH_MEASURE(0.,#925)", 971)
    f.add("TOLERANCED_LENGTH_MEASURE(10.,#925)", 975)


def tapered_hole_feature(f):
    """A ROUND_HOLE at (30, 30), 10 at the top narrowing to 8 at its flat bottom 15 deep
    (DIAMETER_TAPER, issue 17)."""
    f.add("ROUND_HOLE('TAPER1',#900,(#31),#950,#951,#959,#967,#968)", 21)
    f.add("AXIS2_PLACEMENT_3D('TAPER1',#955,#921,#922)", 950)
    f.add("PLANE('TAPER1 DEPTH',#956)", 951)
    f.add("CARTESIAN_POINT('',(30.,30.,0.))", 955)
    f.add("AXIS2_PLACEMENT_3D('TAPER1 DEPTH',#957,#921,#922)", 956)
    f.add("CARTESIAN_POINT('',(0.,0.,-15.))", 957)
    f.add("TOLERANCED_LENGTH_MEASURE(10.,#925)", 959)
    f.add("DIAMETER_TAPER(#960)", 967)
    f.add("TOLERANCED_LENGTH_MEASURE(8.,#925)", 960)
    f.add("FLAT_HOLE_BOTTOM()", 968)


def geometry_cases():
    endmill10 = ("ENDMILL(#711,3,.RIGHT.,.F.,$)", "MILLING_TOOL_DIMENSION(10.,$,$,25.,0.,$,$)")
    endmill8 = ("ENDMILL(#711,3,.RIGHT.,.F.,$)", "MILLING_TOOL_DIMENSION(8.,$,$,25.,0.,$,$)")
    # The slot's path placement read: the end mill of its width along (0, 10)..(0, 50) of the
    # feature passes; the same pass along the feature's x (the placement ignored) gouges.
    shape_program("slot-placed-travel", "a slot along a placed course of travel, cut along it",
                  placed_slot_feature, endmill10,
                  [(0, 10, 5), (0, 10, -5), (0, 50, -5), (0, 50, 5)])
    shape_program("slot-placed-travel-ignored", "the placement of the course of travel ignored",
                  placed_slot_feature, endmill10,
                  [(0, 0, 5), (0, 0, -5), (40, 0, -5), (40, 0, 5)])
    # A tapered hole (10 to 8): an 8 mm tool down its axis passes; a 10 mm one cuts 1 mm into
    # the cone of its wall at the bottom.
    shape_program("taper-good", "a tapered hole cut at its narrowest diameter",
                  tapered_hole_feature, endmill8, [(0, 0, 5), (0, 0, -15), (0, 0, 5)])
    shape_program("taper-too-wide", "a tapered hole cut at its top diameter",
                  tapered_hole_feature, endmill10, [(0, 0, 5), (0, 0, -15), (0, 0, 5)])


def main():
    os.makedirs(os.path.join(HERE, "cases"), exist_ok=True)
    program("good", "a face, a pocket and a hole, machined right")
    # The outer ring's +x side 0.5 mm into the pocket wall (x 65.5 instead of 65 + 5 = 70).
    program("gouge-wall", "the pocket's last ring gouges the +x wall by 0.5 mm",
            pocket_path=[(-12.0, 0.0, 2.0), (12.0, 0.0, -4.0), (-12.0, 0.0, -10.0)] +
            pocket_rings(-10.0, wall_shift=0.5)[1:] + [(-15.0, 0.0, 2.0)])
    # Every level 2 mm short of the floor.
    program("shallow", "the pocket stops 2 mm above its floor",
            pocket_path=[(-12.0, 0.0, 2.0), (12.0, 0.0, -4.0), (-12.0, 0.0, -8.0)] +
            pocket_rings(-8.0)[1:] + [(-15.0, 0.0, 2.0)])
    # Only the outer ring at the floor: a strip along the pocket's middle is never swept.
    program("uncovered-strip", "only the outer ring at the floor leaves a strip in the middle",
            pocket_path=[(-12.0, 0.0, 2.0), (12.0, 0.0, -4.0), (-12.0, 0.0, -10.0)] +
            pocket_rings(-10.0, rings=(0,))[1:] + [(-15.0, 0.0, 2.0)])
    # After the drill, a rapid at z -5 from outside the stock into it.
    program("rapid-into-part", "a rapid at z -5 into the part",
            extra_rapid=[(130.0, 40.0, 20.0), (130.0, 40.0, -5.0), (80.0, 10.0, -5.0)])
    # PLUNGE_HELIX required, but the tool goes straight down in the middle of the pocket.
    program("plunge-helix", "a straight plunge where the strategy asks for a helix",
            pocket_approach="helix",
            pocket_path=[(0.0, 0.0, 2.0), (0.0, 0.0, -10.0)] + pocket_rings(-10.0)[1:] +
            [(-15.0, 0.0, 2.0)])
    # A drill 3 mm too deep in a blind hole.
    program("hole-too-deep", "the drill goes 3 mm below the flat bottom of a blind hole",
            hole_depth=-18.0)
    # POCKET1's outline as a SLOT with flat ends: the same path passes.
    program("slot-flat-ends", "the pocket's outline as a slot with flat ends", slot=True)
    # POCKET1 declared as a SPHERICAL_CAP: not checked (a note), everything else still is.
    program("kind-not-checked", "a feature kind the verifier does not check", step=True)
    shape_cases()
    general_cases()
    geometry_cases()
    return 0


# ---- general outlines (issue 5): an L-shaped polyline pocket, an open pocket, an outside
# profile, each with a right path and a path broken at a known place ----

def quarter(cx, cy, r, a0, n=16):
    return [(cx + r * math.cos(math.radians(a0 + 90.0 * k / n)),
             cy + r * math.sin(math.radians(a0 + 90.0 * k / n))) for k in range(n + 1)]


def general(name, description, feature, path, side=False):
    """One feature and one workingstep with an explicit path, in a 100 x 80 x 20 block whose top
    is z 0. `feature` gives the feature's P21 lines (ids 21 and 950..989) in the feature's frame,
    placed at (20, 15, 0); the end mill is D10 (r 5), no approach strategy."""
    f = P21()
    f.add("PROJECT('%s',#2,(#900),$,$,$)" % name.upper(), 1)
    f.add("WORKPLAN('MAIN',(#11),$,#8,$)", 2)
    f.add("SETUP('SETUP1',#923,#910,(#9))", 8)
    f.add("WORKPIECE_SETUP(#900,#923,$,$,())", 9)
    f.add("MACHINING_WORKINGSTEP('WS PATH',#910,#21,#31,$)", 11)
    for line in feature:
        f.lines.append(line)
    if side:
        f.add("SIDE_FINISH_MILLING(#310,$,'SIDE OP',10.,$,#71,#81,#90,$,$,$,#64,6.,$,0.)", 31)
    else:
        f.add("BOTTOM_AND_SIDE_FINISH_MILLING(#310,$,'POCKET OP',10.,$,#71,#81,#90,$,$,$,#64,"
              "6.,4.,0.,0.)", 31)
    f.add("CONTOUR_PARALLEL($,.T.,.CCW.,.CLIMB.)", 64)
    f.add("MILLING_CUTTING_TOOL('END MILL 10',#710,(#79),70.,$,$)", 71)
    f.add("ENDMILL(#711,3,.RIGHT.,.F.,$)", 710)
    f.add("MILLING_TOOL_DIMENSION(10.,$,$,25.,0.,$,$)", 711)
    f.add("CUTTING_COMPONENT(70.,$,$,$,$)", 79)
    f.add("MILLING_TECHNOLOGY(0.01,.TCP.,$,-50.,$,.F.,.F.,.F.,$)", 81)
    f.add("MILLING_MACHINE_FUNCTIONS(.T.,$,$,.F.,$,(),.F.,$,$,())", 90)
    f.add("WORKPIECE('PART',$,$,$,$,#901,())", 900)
    f.add("BLOCK('STOCK',#902,100.,80.,20.)", 901)
    f.add("AXIS2_PLACEMENT_3D('STOCK CORNER',#903,#921,#922)", 902)
    f.add("CARTESIAN_POINT('',(0.,0.,-20.))", 903)
    f.add("PLANE('SECURITY PLANE',#911)", 910)
    f.add("AXIS2_PLACEMENT_3D('SECURITY',#912,#921,#922)", 911)
    f.add("CARTESIAN_POINT('',(0.,0.,20.))", 912)
    f.add("CARTESIAN_POINT('ORIGIN',(0.,0.,0.))", 920)
    f.add("DIRECTION('Z',(0.,0.,1.))", 921)
    f.add("DIRECTION('X',(1.,0.,0.))", 922)
    f.add("AXIS2_PLACEMENT_3D('IDENTITY',#920,#921,#922)", 923)
    f.add("PLUS_MINUS_VALUE(0.05,0.05,2)", 925)
    f.add("AXIS2_PLACEMENT_3D('FEATURE',#955,#921,#922)", 950)
    f.add("PLANE('DEPTH',#956)", 951)
    f.add("CARTESIAN_POINT('',(20.,15.,0.))", 955)
    f.add("AXIS2_PLACEMENT_3D('DEPTH',#957,#921,#922)", 956)
    f.add("CARTESIAN_POINT('',(0.,0.,-6.))", 957)
    f.next = 2000
    f.add("TOOLPATH_LIST((%s))" % f.polyline("PATH", path), 310)

    def key(line):
        return int(line[1:line.index("=")])

    text = ["ISO-10303-21;", "HEADER;",
            "FILE_DESCRIPTION(('ncpost verify case: %s'),'2;1');" % description.replace("'", "''"),
            "FILE_NAME('%s.stp','2026-11-25T00:00:00',('ncpost'),('ncpost project'),'',"
            "'tests/golden/verify/make_cases.py','');" % name,
            "FILE_SCHEMA(('MACHINING_SCHEMA','MILLING_SCHEMA'));", "ENDSEC;", "DATA;"]
    text += sorted(f.lines, key=key)
    text += ["ENDSEC;", "END-ISO-10303-21;", ""]
    with open(os.path.join(HERE, "cases", name + ".stp"), "w") as out:
        out.write("\n".join(text))


def polyline_lines(points, first_id, closed=True):
    """POLYLINE of 2D points from #first_id on: the points, then the curve (the last id)."""
    lines = []
    ids = []
    for k, (x, y) in enumerate(points):
        lines.append("#%d=CARTESIAN_POINT('',(%.4f,%.4f,0.));" % (first_id + k, x, y))
        ids.append("#%d" % (first_id + k))
    if closed:
        ids.append(ids[0])
    curve = first_id + len(points)
    lines.append("#%d=POLYLINE('',(%s));" % (curve, ",".join(ids)))
    return lines, "#%d" % curve


def l_pocket(name, description, middle=True, shift=0.0):
    """L-shaped pocket (0,0) (60,0) (60,25) (25,25) (25,50) (0,50), orthogonal_radius 5 (= the
    tool radius, so the centre path may go into each convex corner at 5 from both sides), floor
    z -6. The long arm: a line along y 12.5 and its boundary at 5 from the walls; the short arm:
    its boundary at x 5, y 45 and x 20 (moved by `shift` towards the wall at x 25), then a line
    along y at x 12.5 (unless not `middle`), then y 20 back to the long arm."""
    lines, curve = polyline_lines([(0, 0), (60, 0), (60, 25), (25, 25), (25, 50), (0, 50)], 960)
    feature = lines + [
        "#21=CLOSED_POCKET('L POCKET',#900,(#31),#950,#951,(),$,#952,$,#953,#954);",
        "#952=PLANAR_POCKET_BOTTOM_CONDITION();",
        "#953=TOLERANCED_LENGTH_MEASURE(5.,#925);",
        "#954=GENERAL_CLOSED_PROFILE($,%s);" % curve]
    x = 20.0 + shift
    xy = [(5, 12.5), (55, 12.5), (55, 5), (5, 5), (5, 45), (x, 45), (x, 20)]
    xy += [(12.5, 20), (12.5, 45), (12.5, 20)] if middle else []
    xy += [(55, 20), (55, 12.5)]
    z = -6.0
    path = [(5, 12.5, 2)] + [(px, py, z) for px, py in xy] + [(55, 12.5, 2)]
    general(name, description, feature, path)


def open_pocket(name, description, exit_point=None):
    """Walls (50,-20) (0,-20) (0,20) (50,20), open along x 50 (the part's face goes on beyond
    y +-20), orthogonal_radius 5, floor z -6. Zigzag lines along x at y 15..-15 from x 60 (the
    tool radius + 5 past the open side), then along the wall at x 5 and back out along y 15;
    `exit_point` is a last feed at the floor from there."""
    lines, curve = polyline_lines([(50, -20), (0, -20), (0, 20), (50, 20)], 960, closed=False)
    feature = lines + [
        "#21=OPEN_POCKET('OPEN U',#900,(#31),#950,#951,(),$,#952,$,#953,#954,$);",
        "#952=PLANAR_POCKET_BOTTOM_CONDITION();",
        "#953=TOLERANCED_LENGTH_MEASURE(5.,#925);",
        "#954=GENERAL_PROFILE($,%s);" % curve]
    z = -6.0
    path = [(60, 15, 2), (60, 15, z)]
    for k, y in enumerate([15, 7.5, 0, -7.5, -15]):
        a, b = (60, 5) if k % 2 == 0 else (5, 60)
        if k:
            path.append((a, y, z))
        path.append((b, y, z))
    path += [(5, 15, z), (60, 15, z)]
    if exit_point:
        path.append((exit_point[0], exit_point[1], z))
    path.append((path[-1][0], path[-1][1], 2))
    general(name, description, feature, path)


def outside_box(name, description, cut_corner=False):
    """The part: a 40 x 30 polyline outline from (0, 0); the tool goes round it clockwise at 5.01
    (corners arcs of 16 chords), from a lead-in point at (60, 15); `cut_corner` goes straight
    across the (40, 30) corner instead."""
    lines, curve = polyline_lines([(0, 0), (40, 0), (40, 30), (0, 30)], 960)
    feature = lines + [
        "#21=GENERAL_OUTSIDE_PROFILE('BOX',#900,(#31),#950,#951,#958,#954);",
        "#958=LINEAR_PATH($,#959,#921);",
        "#959=TOLERANCED_LENGTH_MEASURE(6.,#925);",
        "#954=GENERAL_CLOSED_PROFILE($,%s);" % curve]
    z = -6.0
    r = 5.01
    ring = [(40 + r, 15)]
    ring += [(40 + r, 30)] if not cut_corner else []
    corner = quarter(40, 30, r, 0)
    ring += corner if not cut_corner else [corner[0], corner[-1]]
    ring += quarter(0, 30, r, 90) + quarter(0, 0, r, 180) + quarter(40, 0, r, 270)
    ring += [(40 + r, 15)]
    ring = list(reversed(ring))  # clockwise: climb with the clockwise spindle
    path = [(60, 15, 2), (60, 15, z)] + [(p[0], p[1], z) for p in ring] + [(60, 15, z), (60, 15, 2)]
    general(name, description, feature, path, side=True)


def general_cases():
    l_pocket("l-pocket", "an L-shaped polyline pocket (orthogonal_radius 5), machined right")
    l_pocket("l-pocket-gouge", "an L-shaped pocket: a line of the short arm 0.8 mm into its wall",
             shift=0.8)
    l_pocket("l-pocket-uncovered", "an L-shaped pocket: the middle line of the short arm left out",
             middle=False)
    open_pocket("open-pocket", "an open pocket, lines running out past its open side")
    open_pocket("open-pocket-face", "an open pocket: a last feed into the part's face beside the "
                "open side", exit_point=(53.0, 24.0))
    outside_box("outside-box", "a general outside profile (polyline), the ring 5.01 outside it")
    outside_box("outside-box-corner", "a general outside profile: the ring cuts across a corner",
                cut_corner=True)


if __name__ == "__main__":
    sys.exit(main())
