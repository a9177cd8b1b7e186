<?xml version="1.0" encoding="UTF-8"?>
<!-- Heidenhain TNC 640, Klartext (conversational) programs (docs/profiles.md,
     heidenhain-tnc640; shared with heidenhain-tnc640-5ax, which imports this file):
       0 BEGIN PGM NAME MM ... n END PGM NAME MM     block numbers 0, 1, 2, ... (ext:block)
       n ; text                                     comments
       TOOL DEF 901 / TOOL CALL 901 Z S3000         pre-selection, tool change with speed
       L X+.. Y+.. Z+.. R0 FMAX | F..               rapid / feed (F modal, FMAX per block)
       L M3 / L M13 ...                             spindle and coolant (M13 = M3 + M8)
       CC X+.. Y+.. then C X+.. Y+.. DR+|DR-        arcs in the XY plane
       CC X+.. Y+.. then CP IPA+.. IZ+.. DR+|DR-    helices and arcs of a full turn or more
       CYCL DEF 9.0 DWELL TIME / 9.1 DWELL s        dwell
       CYCL DEF 200 DRILLING / 203 UNIVERSAL DRILLING + L .. FMAX + CYCL CALL
       L M30                                        end of program
     NURBS are linearised by the renderer. Signed numbers (+/-) everywhere, as the TNC writes
     them. -->
<xsl:stylesheet version="1.0" xmlns:xsl="http://www.w3.org/1999/XSL/Transform"
    xmlns:ext="urn:ncpost:ext" exclude-result-prefixes="ext">
  <xsl:import href="../common/ncpost-common.xsl"/>
  <xsl:output method="text" encoding="UTF-8"/>

  <!-- The SET_FEED_RATE calls that a feed motion must carry as F: those after the previous
       feed motion of the chunk. Looking forward from each SET_FEED_RATE stops at the first
       feed motion, so this stays linear in the chunk. -->
  <xsl:key name="feed-of" match="SET_FEED_RATE"
           use="generate-id(following::*[self::STRAIGHT_FEED or self::ARC_FEED][1])"/>

  <!-- Every block starts with its number; no N. -->
  <xsl:template name="block">
    <xsl:param name="text"/>
    <xsl:value-of select="ext:line(concat(ext:block(), ' ', $text))"/>
    <xsl:text>&#10;</xsl:text>
  </xsl:template>
  <xsl:template name="comment-block">
    <xsl:param name="text"/>
    <xsl:call-template name="block"><xsl:with-param name="text" select="concat('; ', ext:comment($text))"/></xsl:call-template>
  </xsl:template>

  <!-- A number with its sign, as the TNC writes it: +20, -4.5. -->
  <xsl:template name="signed">
    <xsl:param name="value"/>
    <xsl:param name="quantity" select="'length'"/>
    <xsl:variable name="s" select="ext:format($value, $quantity)"/>
    <xsl:choose>
      <xsl:when test="starts-with($s, '-')"><xsl:value-of select="$s"/></xsl:when>
      <xsl:otherwise><xsl:value-of select="concat('+', $s)"/></xsl:otherwise>
    </xsl:choose>
  </xsl:template>

  <xsl:template name="xyz">
    <xsl:param name="x" select="@x"/>
    <xsl:param name="y" select="@y"/>
    <xsl:param name="z" select="@z"/>
    <xsl:variable name="mx"><xsl:call-template name="signed"><xsl:with-param name="value" select="ext:setup-x($x, $y, $z)"/></xsl:call-template></xsl:variable>
    <xsl:variable name="my"><xsl:call-template name="signed"><xsl:with-param name="value" select="ext:setup-y($x, $y, $z)"/></xsl:call-template></xsl:variable>
    <xsl:variable name="mz"><xsl:call-template name="signed"><xsl:with-param name="value" select="ext:setup-z($x, $y, $z)"/></xsl:call-template></xsl:variable>
    <xsl:value-of select="concat(' X', $mx, ' Y', $my, ' Z', $mz)"/>
    <!-- A five-axis profile's rotary axes (heidenhain-tnc640-5ax; none in three-axis posts). -->
    <xsl:if test="@a and contains($rotary_axes, 'A')"><xsl:text> A</xsl:text><xsl:call-template name="signed"><xsl:with-param name="value" select="@a"/><xsl:with-param name="quantity" select="'angle'"/></xsl:call-template></xsl:if>
    <xsl:if test="@b and contains($rotary_axes, 'B')"><xsl:text> B</xsl:text><xsl:call-template name="signed"><xsl:with-param name="value" select="@b"/><xsl:with-param name="quantity" select="'angle'"/></xsl:call-template></xsl:if>
    <xsl:if test="@c and contains($rotary_axes, 'C')"><xsl:text> C</xsl:text><xsl:call-template name="signed"><xsl:with-param name="value" select="@c"/><xsl:with-param name="quantity" select="'angle'"/></xsl:call-template></xsl:if>
  </xsl:template>

  <xsl:template name="units-word">
    <xsl:choose><xsl:when test="ext:units() = 'inch'">INCH</xsl:when><xsl:otherwise>MM</xsl:otherwise></xsl:choose>
  </xsl:template>
  <!-- Program names: letters, digits and underscores. -->
  <xsl:template name="program-name">
    <xsl:variable name="clean" select="translate(@name, ' -.,#/:*+=%()', '_____________')"/>
    <xsl:choose>
      <xsl:when test="$clean = ''"><xsl:value-of select="concat('NCPOST', $program_number)"/></xsl:when>
      <xsl:otherwise><xsl:value-of select="$clean"/></xsl:otherwise>
    </xsl:choose>
  </xsl:template>

  <xsl:template match="PROJECT_BEGIN">
    <xsl:variable name="name"><xsl:call-template name="program-name"/></xsl:variable>
    <xsl:variable name="units"><xsl:call-template name="units-word"/></xsl:variable>
    <xsl:call-template name="block"><xsl:with-param name="text" select="concat('BEGIN PGM ', $name, ' ', $units)"/></xsl:call-template>
    <xsl:call-template name="comment-block">
      <xsl:with-param name="text" select="concat('PROJECT #', @id, ' ', @name)"/>
    </xsl:call-template>
  </xsl:template>
  <xsl:template match="PROJECT_END">
    <xsl:variable name="name"><xsl:call-template name="program-name"/></xsl:variable>
    <xsl:variable name="units"><xsl:call-template name="units-word"/></xsl:variable>
    <xsl:call-template name="block"><xsl:with-param name="text" select="concat('END PGM ', $name, ' ', $units)"/></xsl:call-template>
  </xsl:template>

  <!-- The working plane follows the tool axis (TOOL CALL .. Z): XY. -->
  <xsl:template match="SELECT_PLANE"/>

  <!-- " R0" the first time (radius compensation off is modal). -->
  <xsl:template name="r0">
    <xsl:variable name="r" select="ext:modal('radius', 'R0')"/>
    <xsl:if test="$r != ''"><xsl:value-of select="concat(' ', $r)"/></xsl:if>
  </xsl:template>
  <!-- " F.." when a SET_FEED_RATE came since the previous feed motion and changed the feed. -->
  <xsl:template name="feed-word">
    <xsl:variable name="set" select="key('feed-of', generate-id())"/>
    <xsl:if test="$set">
      <xsl:variable name="f" select="ext:modal('feed', concat('F', ext:format($set[last()]/@rate, 'feed')))"/>
      <xsl:if test="$f != ''"><xsl:value-of select="concat(' ', $f)"/></xsl:if>
    </xsl:if>
  </xsl:template>

  <xsl:template match="STRAIGHT_TRAVERSE">
    <xsl:variable name="axes"><xsl:call-template name="xyz"/></xsl:variable>
    <xsl:variable name="r"><xsl:call-template name="r0"/></xsl:variable>
    <xsl:call-template name="block"><xsl:with-param name="text" select="concat('L', $axes, $r, ' FMAX')"/></xsl:call-template>
    <xsl:value-of select="ext:moved-to(@x, @y, @z)"/>
  </xsl:template>
  <xsl:template match="STRAIGHT_FEED">
    <xsl:variable name="axes"><xsl:call-template name="xyz"/></xsl:variable>
    <xsl:variable name="r"><xsl:call-template name="r0"/></xsl:variable>
    <xsl:variable name="f"><xsl:call-template name="feed-word"/></xsl:variable>
    <xsl:call-template name="block"><xsl:with-param name="text" select="concat('L', $axes, $r, $f)"/></xsl:call-template>
    <xsl:value-of select="ext:moved-to(@x, @y, @z)"/>
  </xsl:template>

  <!-- Arcs: the centre CC, then C to the end point, or CP with the total angle IPA (full turns
       included) and the height change IZ for helices and arcs of 360 degrees or more. -->
  <xsl:template match="ARC_FEED">
    <xsl:if test="not(@plane = 'xy')">
      <xsl:message terminate="yes">ARC_FEED outside the XY plane: not supported by this profile (tool axis Z)</xsl:message>
    </xsl:if>
    <xsl:variable name="sx" select="ext:position('x')"/>
    <xsl:variable name="sy" select="ext:position('y')"/>
    <xsl:variable name="sz" select="ext:position('z')"/>
    <xsl:variable name="cx"><xsl:call-template name="signed"><xsl:with-param name="value" select="ext:setup-x(@cx, @cy, @z)"/></xsl:call-template></xsl:variable>
    <xsl:variable name="cy"><xsl:call-template name="signed"><xsl:with-param name="value" select="ext:setup-y(@cx, @cy, @z)"/></xsl:call-template></xsl:variable>
    <xsl:call-template name="block"><xsl:with-param name="text" select="concat('CC X', $cx, ' Y', $cy)"/></xsl:call-template>
    <xsl:variable name="dr"><xsl:choose><xsl:when test="@rotation &gt; 0">DR+</xsl:when><xsl:otherwise>DR-</xsl:otherwise></xsl:choose></xsl:variable>
    <xsl:variable name="f"><xsl:call-template name="feed-word"/></xsl:variable>
    <xsl:variable name="sweep" select="ext:arc-sweep($sx, $sy, @x, @y, @cx, @cy, @rotation)"/>
    <xsl:variable name="dz" select="ext:setup-z(@x, @y, @z) - ext:setup-z($sx, $sy, $sz)"/>
    <xsl:choose>
      <xsl:when test="$sweep &gt;= 359.999 or $sweep &lt;= -359.999 or ext:format($dz, 'length') != '0'">
        <xsl:variable name="ipa"><xsl:call-template name="signed"><xsl:with-param name="value" select="$sweep"/><xsl:with-param name="quantity" select="'angle'"/></xsl:call-template></xsl:variable>
        <xsl:variable name="iz"><xsl:call-template name="signed"><xsl:with-param name="value" select="$dz"/></xsl:call-template></xsl:variable>
        <xsl:call-template name="block"><xsl:with-param name="text" select="concat('CP IPA', $ipa, ' IZ', $iz, ' ', $dr, $f)"/></xsl:call-template>
      </xsl:when>
      <xsl:otherwise>
        <xsl:variable name="ex"><xsl:call-template name="signed"><xsl:with-param name="value" select="ext:setup-x(@x, @y, @z)"/></xsl:call-template></xsl:variable>
        <xsl:variable name="ey"><xsl:call-template name="signed"><xsl:with-param name="value" select="ext:setup-y(@x, @y, @z)"/></xsl:call-template></xsl:variable>
        <xsl:call-template name="block"><xsl:with-param name="text" select="concat('C X', $ex, ' Y', $ey, ' ', $dr, $f)"/></xsl:call-template>
      </xsl:otherwise>
    </xsl:choose>
    <xsl:value-of select="ext:moved-to(@x, @y, @z)"/>
  </xsl:template>

  <!-- F is written with the next feed motion (see feed-of). A feed set with no feed motion
       after it in this transform is written at once as "TOOL CALL Z F..", a tool call
       without a tool number that only sets data (the TNC keeps a TOOL CALL's F until the next F), so that a later transform's
       feed motions find it in force. -->
  <xsl:template match="SET_FEED_RATE">
    <xsl:if test="not(following::*[self::STRAIGHT_FEED or self::ARC_FEED][1])">
      <xsl:variable name="f" select="ext:modal('feed', concat('F', ext:format(@rate, 'feed')))"/>
      <xsl:if test="$f != ''">
        <xsl:call-template name="block"><xsl:with-param name="text" select="concat('TOOL CALL Z ', $f)"/></xsl:call-template>
      </xsl:if>
    </xsl:if>
  </xsl:template>

  <!-- Tools: TOOL CALL takes the spindle speed that follows the change closely. -->
  <xsl:template match="SELECT_TOOL">
    <xsl:call-template name="block"><xsl:with-param name="text" select="concat('TOOL DEF ', @slot)"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="CHANGE_TOOL">
    <xsl:variable name="s" select="following-sibling::*[position() &lt;= 4][self::SET_SPINDLE_SPEED][1]"/>
    <xsl:variable name="speed"><xsl:if test="$s"><xsl:value-of select="concat(' S', ext:format($s/@rpm, 'speed'))"/></xsl:if></xsl:variable>
    <xsl:call-template name="block"><xsl:with-param name="text" select="concat('TOOL CALL ', @slot, ' Z', $speed)"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="SET_SPINDLE_SPEED">
    <xsl:if test="not(preceding-sibling::*[position() &lt;= 4][self::CHANGE_TOOL])">
      <xsl:call-template name="block"><xsl:with-param name="text" select="concat('TOOL CALL Z S', ext:format(@rpm, 'speed'))"/></xsl:call-template>
    </xsl:if>
  </xsl:template>
  <!-- The TNC applies the tool length with TOOL CALL. -->
  <xsl:template match="USE_TOOL_LENGTH_OFFSET"/>

  <xsl:template match="START_SPINDLE_CLOCKWISE | START_SPINDLE_COUNTERCLOCKWISE">
    <xsl:variable name="m">
      <xsl:choose>
        <xsl:when test="self::START_SPINDLE_CLOCKWISE and following-sibling::*[1][self::FLOOD_ON]">M13</xsl:when>
        <xsl:when test="self::START_SPINDLE_CLOCKWISE">M3</xsl:when>
        <xsl:when test="following-sibling::*[1][self::FLOOD_ON]">M14</xsl:when>
        <xsl:otherwise>M4</xsl:otherwise>
      </xsl:choose>
    </xsl:variable>
    <xsl:call-template name="block"><xsl:with-param name="text" select="concat('L ', $m)"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="FLOOD_ON">
    <xsl:if test="not(preceding-sibling::*[1][self::START_SPINDLE_CLOCKWISE or self::START_SPINDLE_COUNTERCLOCKWISE])">
      <xsl:call-template name="block"><xsl:with-param name="text" select="'L M8'"/></xsl:call-template>
    </xsl:if>
  </xsl:template>
  <xsl:template match="MIST_ON">
    <xsl:call-template name="block"><xsl:with-param name="text" select="'L M7'"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="FLOOD_OFF | MIST_OFF">
    <xsl:call-template name="block"><xsl:with-param name="text" select="'L M9'"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="STOP_SPINDLE_TURNING">
    <xsl:call-template name="block"><xsl:with-param name="text" select="'L M5'"/></xsl:call-template>
  </xsl:template>

  <xsl:template name="dwell">
    <xsl:param name="seconds"/>
    <xsl:call-template name="block"><xsl:with-param name="text" select="'CYCL DEF 9.0 DWELL TIME'"/></xsl:call-template>
    <xsl:call-template name="block"><xsl:with-param name="text" select="concat('CYCL DEF 9.1 DWELL ', ext:format($seconds, 'dwell'))"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="DWELL">
    <xsl:call-template name="dwell"><xsl:with-param name="seconds" select="@seconds"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="MESSAGE">
    <xsl:call-template name="comment-block"><xsl:with-param name="text" select="concat('MSG ', string(.))"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="OPTIONAL_PROGRAM_STOP">
    <xsl:call-template name="block"><xsl:with-param name="text" select="'L M1'"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="PROGRAM_STOP">
    <xsl:call-template name="block"><xsl:with-param name="text" select="'STOP'"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="PROGRAM_END">
    <xsl:call-template name="block"><xsl:with-param name="text" select="'L M30'"/></xsl:call-template>
  </xsl:template>

  <!-- Cycles 200 and 203. Q203 (surface) = R plane - Q200, so that the rapid approach ends at
       the R plane; Q200 (set-up clearance) = the cycle's peck clearance, which cycle 203 also
       keeps above the previous depth when it goes back into the hole; Q204 = safe level -
       Q203; Q201 = bottom - Q203 (negative). Retraction at FMAX (Q208). The hole is
       positioned at the safe level, then CYCL CALL. -->
  <xsl:template name="q">
    <xsl:param name="name"/>
    <xsl:param name="value"/>
    <xsl:param name="quantity" select="'length'"/>
    <xsl:param name="label"/>
    <xsl:param name="last" select="false()"/>
    <xsl:variable name="v"><xsl:call-template name="signed"><xsl:with-param name="value" select="$value"/><xsl:with-param name="quantity" select="$quantity"/></xsl:call-template></xsl:variable>
    <xsl:value-of select="ext:line(concat('  ', $name, '=', $v, ' ;', $label, substring(' ~', 1, 2 * not($last))))"/>
    <xsl:text>&#10;</xsl:text>
  </xsl:template>
  <xsl:template name="cycle-call">
    <xsl:variable name="safe"><xsl:call-template name="xyz"><xsl:with-param name="z" select="@safe_z"/></xsl:call-template></xsl:variable>
    <xsl:variable name="r"><xsl:call-template name="r0"/></xsl:variable>
    <xsl:call-template name="block"><xsl:with-param name="text" select="concat('L', $safe, $r, ' FMAX')"/></xsl:call-template>
    <xsl:call-template name="block"><xsl:with-param name="text" select="'CYCL CALL'"/></xsl:call-template>
    <xsl:value-of select="ext:moved-to(@x, @y, @safe_z)"/>
  </xsl:template>

  <xsl:template match="DRILL_CYCLE | PECK_DRILL_CYCLE">
    <xsl:variable name="q200">
      <xsl:choose><xsl:when test="@peck_clearance"><xsl:value-of select="@peck_clearance"/></xsl:when><xsl:otherwise>0</xsl:otherwise></xsl:choose>
    </xsl:variable>
    <xsl:variable name="surface" select="ext:setup-z(@x, @y, @r_z) - $q200"/>
    <xsl:variable name="depth" select="ext:setup-z(@x, @y, @bottom_z) - $surface"/>
    <xsl:variable name="second" select="ext:setup-z(@x, @y, @safe_z) - $surface"/>
    <xsl:variable name="dwell" select="number(@dwell)"/>
    <xsl:choose>
      <xsl:when test="self::DRILL_CYCLE">
        <xsl:call-template name="block"><xsl:with-param name="text" select="'CYCL DEF 200 DRILLING ~'"/></xsl:call-template>
        <xsl:call-template name="q"><xsl:with-param name="name" select="'Q200'"/><xsl:with-param name="value" select="$q200"/><xsl:with-param name="label" select="'SET-UP CLEARANCE'"/></xsl:call-template>
        <xsl:call-template name="q"><xsl:with-param name="name" select="'Q201'"/><xsl:with-param name="value" select="$depth"/><xsl:with-param name="label" select="'DEPTH'"/></xsl:call-template>
        <xsl:call-template name="q"><xsl:with-param name="name" select="'Q206'"/><xsl:with-param name="value" select="@feed"/><xsl:with-param name="quantity" select="'feed'"/><xsl:with-param name="label" select="'FEED RATE FOR PLNGNG'"/></xsl:call-template>
        <xsl:call-template name="q"><xsl:with-param name="name" select="'Q202'"/><xsl:with-param name="value" select="-$depth"/><xsl:with-param name="label" select="'PLUNGING DEPTH'"/></xsl:call-template>
        <xsl:call-template name="q"><xsl:with-param name="name" select="'Q210'"/><xsl:with-param name="value" select="0"/><xsl:with-param name="quantity" select="'dwell'"/><xsl:with-param name="label" select="'DWELL TIME AT TOP'"/></xsl:call-template>
        <xsl:call-template name="q"><xsl:with-param name="name" select="'Q203'"/><xsl:with-param name="value" select="$surface"/><xsl:with-param name="label" select="'SURFACE COORDINATE'"/></xsl:call-template>
        <xsl:call-template name="q"><xsl:with-param name="name" select="'Q204'"/><xsl:with-param name="value" select="$second"/><xsl:with-param name="label" select="'2ND SET-UP CLEARANCE'"/></xsl:call-template>
        <xsl:call-template name="q"><xsl:with-param name="name" select="'Q211'"/><xsl:with-param name="value" select="$dwell"/><xsl:with-param name="quantity" select="'dwell'"/><xsl:with-param name="label" select="'DWELL TIME AT DEPTH'"/></xsl:call-template>
        <xsl:call-template name="q"><xsl:with-param name="name" select="'Q395'"/><xsl:with-param name="value" select="0"/><xsl:with-param name="quantity" select="'speed'"/><xsl:with-param name="label" select="'DEPTH REFERENCE'"/><xsl:with-param name="last" select="true()"/></xsl:call-template>
      </xsl:when>
      <xsl:otherwise>
        <xsl:variable name="breaks"><xsl:choose><xsl:when test="@peck_retract &gt; 0">99</xsl:when><xsl:otherwise>0</xsl:otherwise></xsl:choose></xsl:variable>
        <xsl:call-template name="block"><xsl:with-param name="text" select="'CYCL DEF 203 UNIVERSAL DRILLING ~'"/></xsl:call-template>
        <xsl:call-template name="q"><xsl:with-param name="name" select="'Q200'"/><xsl:with-param name="value" select="$q200"/><xsl:with-param name="label" select="'SET-UP CLEARANCE'"/></xsl:call-template>
        <xsl:call-template name="q"><xsl:with-param name="name" select="'Q201'"/><xsl:with-param name="value" select="$depth"/><xsl:with-param name="label" select="'DEPTH'"/></xsl:call-template>
        <xsl:call-template name="q"><xsl:with-param name="name" select="'Q206'"/><xsl:with-param name="value" select="@feed"/><xsl:with-param name="quantity" select="'feed'"/><xsl:with-param name="label" select="'FEED RATE FOR PLNGNG'"/></xsl:call-template>
        <xsl:call-template name="q"><xsl:with-param name="name" select="'Q202'"/><xsl:with-param name="value" select="@peck"/><xsl:with-param name="label" select="'PLUNGING DEPTH'"/></xsl:call-template>
        <xsl:call-template name="q"><xsl:with-param name="name" select="'Q210'"/><xsl:with-param name="value" select="0"/><xsl:with-param name="quantity" select="'dwell'"/><xsl:with-param name="label" select="'DWELL TIME AT TOP'"/></xsl:call-template>
        <xsl:call-template name="q"><xsl:with-param name="name" select="'Q203'"/><xsl:with-param name="value" select="$surface"/><xsl:with-param name="label" select="'SURFACE COORDINATE'"/></xsl:call-template>
        <xsl:call-template name="q"><xsl:with-param name="name" select="'Q204'"/><xsl:with-param name="value" select="$second"/><xsl:with-param name="label" select="'2ND SET-UP CLEARANCE'"/></xsl:call-template>
        <xsl:call-template name="q"><xsl:with-param name="name" select="'Q212'"/><xsl:with-param name="value" select="0"/><xsl:with-param name="label" select="'DECREMENT'"/></xsl:call-template>
        <xsl:call-template name="q"><xsl:with-param name="name" select="'Q213'"/><xsl:with-param name="value" select="$breaks"/><xsl:with-param name="quantity" select="'speed'"/><xsl:with-param name="label" select="'NR OF BREAKS'"/></xsl:call-template>
        <xsl:call-template name="q"><xsl:with-param name="name" select="'Q205'"/><xsl:with-param name="value" select="0"/><xsl:with-param name="label" select="'MIN. PLUNGING DEPTH'"/></xsl:call-template>
        <xsl:call-template name="q"><xsl:with-param name="name" select="'Q211'"/><xsl:with-param name="value" select="$dwell"/><xsl:with-param name="quantity" select="'dwell'"/><xsl:with-param name="label" select="'DWELL TIME AT DEPTH'"/></xsl:call-template>
        <xsl:value-of select="ext:line('  Q208=FMAX ;RETRACTION FEED RATE ~')"/>
        <xsl:text>&#10;</xsl:text>
        <xsl:call-template name="q"><xsl:with-param name="name" select="'Q256'"/><xsl:with-param name="value" select="number(@peck_retract)"/><xsl:with-param name="label" select="'DIST FOR CHIP BRKNG'"/></xsl:call-template>
        <xsl:call-template name="q"><xsl:with-param name="name" select="'Q395'"/><xsl:with-param name="value" select="0"/><xsl:with-param name="quantity" select="'speed'"/><xsl:with-param name="label" select="'DEPTH REFERENCE'"/><xsl:with-param name="last" select="true()"/></xsl:call-template>
      </xsl:otherwise>
    </xsl:choose>
    <xsl:call-template name="cycle-call"/>
  </xsl:template>

  <!-- Tapping and boring: the motions canon::expand_cycle gives, as L blocks (no TNC cycle of
       the same motion is used yet). -->
  <xsl:template name="z-block">
    <xsl:param name="z"/>
    <xsl:param name="rapid" select="false()"/>
    <xsl:param name="feed" select="''"/>
    <xsl:variable name="axes"><xsl:call-template name="xyz"><xsl:with-param name="z" select="$z"/></xsl:call-template></xsl:variable>
    <xsl:choose>
      <xsl:when test="$rapid"><xsl:call-template name="block"><xsl:with-param name="text" select="concat('L', $axes, ' FMAX')"/></xsl:call-template></xsl:when>
      <xsl:otherwise><xsl:call-template name="block"><xsl:with-param name="text" select="concat('L', $axes, $feed)"/></xsl:call-template></xsl:otherwise>
    </xsl:choose>
  </xsl:template>
  <xsl:template match="TAP_CYCLE | BORE_CYCLE | REAM_CYCLE">
    <xsl:variable name="f" select="concat(' F', ext:format(@feed, 'feed'))"/>
    <xsl:value-of select="substring(ext:modal('feed', concat('F', ext:format(@feed, 'feed'))), 1, 0)"/>
    <xsl:call-template name="z-block"><xsl:with-param name="z" select="@safe_z"/><xsl:with-param name="rapid" select="true()"/></xsl:call-template>
    <xsl:call-template name="z-block"><xsl:with-param name="z" select="@r_z"/><xsl:with-param name="rapid" select="true()"/></xsl:call-template>
    <xsl:call-template name="z-block"><xsl:with-param name="z" select="@bottom_z"/><xsl:with-param name="feed" select="$f"/></xsl:call-template>
    <xsl:variable name="out"><xsl:choose><xsl:when test="@hand = 'left'">L M3</xsl:when><xsl:otherwise>L M4</xsl:otherwise></xsl:choose></xsl:variable>
    <xsl:variable name="in"><xsl:choose><xsl:when test="@hand = 'left'">L M4</xsl:when><xsl:otherwise>L M3</xsl:otherwise></xsl:choose></xsl:variable>
    <xsl:choose>
      <xsl:when test="self::TAP_CYCLE">
        <xsl:call-template name="block"><xsl:with-param name="text" select="'L M5'"/></xsl:call-template>
        <xsl:call-template name="block"><xsl:with-param name="text" select="$out"/></xsl:call-template>
        <xsl:if test="@dwell &gt; 0"><xsl:call-template name="dwell"><xsl:with-param name="seconds" select="@dwell"/></xsl:call-template></xsl:if>
        <xsl:call-template name="z-block"><xsl:with-param name="z" select="@r_z"/></xsl:call-template>
        <xsl:call-template name="block"><xsl:with-param name="text" select="'L M5'"/></xsl:call-template>
        <xsl:call-template name="block"><xsl:with-param name="text" select="$in"/></xsl:call-template>
      </xsl:when>
      <xsl:when test="@spindle_stop = 'true'">
        <xsl:if test="@dwell &gt; 0"><xsl:call-template name="dwell"><xsl:with-param name="seconds" select="@dwell"/></xsl:call-template></xsl:if>
        <xsl:call-template name="block"><xsl:with-param name="text" select="'L M5'"/></xsl:call-template>
      </xsl:when>
      <xsl:otherwise>
        <xsl:if test="@dwell &gt; 0"><xsl:call-template name="dwell"><xsl:with-param name="seconds" select="@dwell"/></xsl:call-template></xsl:if>
        <xsl:call-template name="z-block"><xsl:with-param name="z" select="@r_z"/></xsl:call-template>
      </xsl:otherwise>
    </xsl:choose>
    <xsl:call-template name="z-block"><xsl:with-param name="z" select="@safe_z"/><xsl:with-param name="rapid" select="true()"/></xsl:call-template>
    <xsl:if test="@spindle_stop = 'true'">
      <xsl:call-template name="block"><xsl:with-param name="text" select="'L M3'"/></xsl:call-template>
    </xsl:if>
    <xsl:value-of select="ext:moved-to(@x, @y, @safe_z)"/>
  </xsl:template>
</xsl:stylesheet>
