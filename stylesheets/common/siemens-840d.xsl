<?xml version="1.0" encoding="UTF-8"?>
<!-- Siemens Sinumerik 840D sl (docs/profiles.md, siemens-840d): the common templates with the
     Sinumerik dialect, shared by siemens-840d and siemens-840d-5ax:
       %_N_<NAME>_MPF / ;$PATH=/_N_MPF_DIR   the archive header of a main program
       N10, N20, ...                         block numbers (ext:block)
       ; text                                comments, MSG("...") for messages
       G17 G71 G90 G94 G40                   plane, metric, absolute, feed per minute
       G2/G3 X Y Z I J K [TURN=n]            incremental centre, TURN = full turns before the end
       T901 M6, D1 / D0                      tool change, tool offset on / off
       G4 F<s>                               dwell in seconds
       CYCLE81/82/83/85                      drilling cycles at the current X Y, after "G0 X Y Z"
       BSPLINE SD= PL= PW=                   NURBS: one block per control point after the start
       M30                                   end of program -->
<xsl:stylesheet version="1.0" xmlns:xsl="http://www.w3.org/1999/XSL/Transform"
    xmlns:ext="urn:ncpost:ext" exclude-result-prefixes="ext">
  <xsl:import href="ncpost-common.xsl"/>
  <xsl:output method="text" encoding="UTF-8"/>

  <!-- Sinumerik program names: letters, digits and underscores, the first two characters
       letters (NC is put in front otherwise). -->
  <xsl:template name="program-name">
    <xsl:param name="name"/>
    <xsl:variable name="clean" select="translate($name, ' -.,#/:*+=%()', '_____________')"/>
    <xsl:variable name="letters" select="'ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz'"/>
    <xsl:choose>
      <xsl:when test="$clean = ''"><xsl:value-of select="concat('NCPOST', $program_number)"/></xsl:when>
      <xsl:when test="string-length($clean) &lt; 2 or translate(substring($clean, 1, 2), $letters, '') != ''">
        <xsl:value-of select="concat('NC', $clean)"/>
      </xsl:when>
      <xsl:otherwise><xsl:value-of select="$clean"/></xsl:otherwise>
    </xsl:choose>
  </xsl:template>

  <!-- Comments are lines of their own, without a block number. -->
  <xsl:template name="comment-block">
    <xsl:param name="text"/>
    <xsl:value-of select="ext:line(concat('; ', ext:comment($text)))"/>
    <xsl:text>&#10;</xsl:text>
  </xsl:template>

  <xsl:template match="PROJECT_BEGIN">
    <xsl:variable name="name"><xsl:call-template name="program-name"><xsl:with-param name="name" select="@name"/></xsl:call-template></xsl:variable>
    <xsl:value-of select="concat('%_N_', $name, '_MPF')"/>
    <xsl:text>&#10;;$PATH=/_N_MPF_DIR&#10;</xsl:text>
    <xsl:call-template name="comment-block">
      <xsl:with-param name="text" select="concat('PROJECT #', @id, ' ', @name)"/>
    </xsl:call-template>
    <xsl:variable name="units">
      <xsl:choose><xsl:when test="ext:units() = 'inch'">G70</xsl:when><xsl:otherwise>G71</xsl:otherwise></xsl:choose>
    </xsl:variable>
    <xsl:value-of select="substring(ext:modal('plane', 'G17'), 1, 0)"/>
    <xsl:call-template name="block">
      <xsl:with-param name="text" select="concat('G17 ', $units, ' G90 G94 G40')"/>
    </xsl:call-template>
  </xsl:template>

  <xsl:template match="MESSAGE">
    <xsl:call-template name="block">
      <xsl:with-param name="text" select="concat('MSG(&quot;', ext:comment(string(.)), '&quot;)')"/>
    </xsl:call-template>
  </xsl:template>

  <!-- The common arc with TURN= instead of P for the full turns before the end point. -->
  <xsl:template match="ARC_FEED">
    <xsl:if test="not(@plane)">
      <xsl:message terminate="yes">ARC_FEED in a tilted plane has no G2/G3 form on this controller</xsl:message>
    </xsl:if>
    <!-- 0: xy (or none), 1: yz, 2: xz -->
    <xsl:variable name="pl" select="(@plane = 'yz') + 2 * (@plane = 'xz')"/>
    <xsl:variable name="plane" select="ext:modal('plane', substring('G17G19G18', 1 + 3 * $pl, 3))"/>
    <xsl:if test="$plane != ''">
      <xsl:call-template name="block"><xsl:with-param name="text" select="$plane"/></xsl:call-template>
    </xsl:if>
    <xsl:variable name="g" select="substring('G2G3', 1 + 2 * (@rotation &gt; 0), 2)"/>
    <xsl:variable name="turns" select="substring(concat(' TURN=', translate(@rotation, '-', '') - 1), 1, 1000 * (@rotation &gt; 1 or @rotation &lt; -1))"/>
    <xsl:choose>
      <xsl:when test="@a or @b or @c">
        <xsl:variable name="axes"><xsl:call-template name="xyz"/></xsl:variable>
        <xsl:variable name="centre"><xsl:call-template name="arc-ijk"/></xsl:variable>
        <xsl:call-template name="block">
          <xsl:with-param name="text" select="concat($g, $axes, $centre, $turns)"/>
        </xsl:call-template>
      </xsl:when>
      <!-- "xyz", "arc-ijk" and "block", inline (see ncpost-common.xsl). -->
      <xsl:otherwise>
        <xsl:variable name="x" select="number(@x)"/>
        <xsl:variable name="y" select="number(@y)"/>
        <xsl:variable name="z" select="number(@z)"/>
        <xsl:variable name="cx" select="number(@cx)"/>
        <xsl:variable name="cy" select="number(@cy)"/>
        <xsl:variable name="cz" select="number(@cz)"/>
        <xsl:variable name="axes" select="concat(' X', ext:format(ext:setup-x($x, $y, $z), 'length'),
                       ' Y', ext:format(ext:setup-y($x, $y, $z), 'length'),
                       ' Z', ext:format(ext:setup-z($x, $y, $z), 'length'))"/>
        <xsl:variable name="sx" select="ext:position('x')"/>
        <xsl:variable name="sy" select="ext:position('y')"/>
        <xsl:variable name="sz" select="ext:position('z')"/>
        <xsl:variable name="text" select="concat($g, $axes,
            substring(concat(' I', ext:format(ext:arc-i(ext:setup-x($sx, $sy, $sz), ext:setup-x($cx, $cy, $cz)), 'length')), 1, 1000 * ($pl != 1)),
            substring(concat(' J', ext:format(ext:arc-j(ext:setup-y($sx, $sy, $sz), ext:setup-y($cx, $cy, $cz)), 'length')), 1, 1000 * ($pl != 2)),
            substring(concat(' K', ext:format(ext:arc-k(ext:setup-z($sx, $sy, $sz), ext:setup-z($cx, $cy, $cz)), 'length')), 1, 1000 * ($pl != 0)),
            $turns)"/>
        <xsl:value-of select="ext:block-line($text)"/>
        <xsl:text>&#10;</xsl:text>
      </xsl:otherwise>
    </xsl:choose>
    <xsl:value-of select="ext:moved-to(@x, @y, @z)"/>
  </xsl:template>

  <xsl:template match="USE_TOOL_LENGTH_OFFSET">
    <xsl:choose>
      <xsl:when test="@length = 0">
        <xsl:call-template name="block"><xsl:with-param name="text" select="'D0'"/></xsl:call-template>
      </xsl:when>
      <xsl:otherwise>
        <xsl:call-template name="block"><xsl:with-param name="text" select="'D1'"/></xsl:call-template>
      </xsl:otherwise>
    </xsl:choose>
  </xsl:template>

  <xsl:template match="DWELL">
    <xsl:call-template name="block"><xsl:with-param name="text" select="concat('G4 F', ext:format(@seconds, 'dwell'))"/></xsl:call-template>
  </xsl:template>

  <!-- NURBS: Sinumerik's B spline. The start point is the current position (the canonical
       NURBS starts there); each further control point is one block with its weight PW. PL is
       the knot interval that ends at the point's knot, written while the knots still rise
       (the last degree knots repeat the end knot). Weights are divided by the start point's
       weight (the curve does not change) because the start point carries none; PW must then
       lie in 0..3 (4 decimals). -->
  <xsl:template name="nurbs-number">
    <xsl:param name="value"/>
    <xsl:value-of select="format-number($value, '0.######')"/>
  </xsl:template>
  <xsl:template match="NURBS_FEED">
    <xsl:variable name="degree" select="number(@degree)"/>
    <xsl:variable name="w0" select="number(point[1]/@w)"/>
    <xsl:if test="$degree &lt; 1 or $degree &gt; 3">
      <xsl:message terminate="yes">NURBS_FEED of degree above 3: BSPLINE takes SD=1..3 (set capabilities.nurbs to linearize)</xsl:message>
    </xsl:if>
    <xsl:if test="point[@w div $w0 &gt; 3]">
      <xsl:message terminate="yes">NURBS_FEED weight ratio above 3: BSPLINE PW takes 0..3 (set capabilities.nurbs to linearize)</xsl:message>
    </xsl:if>
    <xsl:variable name="knots" select="knot"/>
    <xsl:for-each select="point[position() &gt; 1]">
      <xsl:variable name="i" select="position()"/>
      <xsl:variable name="axes"><xsl:call-template name="xyz"/></xsl:variable>
      <xsl:variable name="pl" select="$knots[$degree + $i + 1]/@value - $knots[$degree + $i]/@value"/>
      <xsl:variable name="plword">
        <xsl:if test="$pl &gt; 0">
          <xsl:text> PL=</xsl:text>
          <xsl:call-template name="nurbs-number"><xsl:with-param name="value" select="$pl"/></xsl:call-template>
        </xsl:if>
      </xsl:variable>
      <xsl:variable name="start">
        <xsl:if test="$i = 1"><xsl:value-of select="concat('BSPLINE SD=', $degree, ' ')"/></xsl:if>
      </xsl:variable>
      <xsl:call-template name="block">
        <xsl:with-param name="text" select="concat($start, substring($axes, 2), ' PW=', format-number(@w div $w0, '0.####'), $plword)"/>
      </xsl:call-template>
    </xsl:for-each>
    <xsl:value-of select="ext:moved-to(point[last()]/@x, point[last()]/@y, point[last()]/@z)"/>
  </xsl:template>

  <!-- Cycles. The hole is positioned with G0 at the safe level, then the cycle runs at the
       current X Y: RTP = safe level, RFP = R plane with SDIS = 0 (so the rapid approach ends at
       the R plane), DP = bottom; the cutting feed is the F in force, written before. Kinds
       without a Sinumerik cycle of the same motion (tapping, boring with spindle stop) are
       written as the motions canon::expand_cycle would give. -->
  <xsl:template name="cycle-start">
    <xsl:call-template name="block"><xsl:with-param name="text" select="concat('F', ext:format(@feed, 'feed'))"/></xsl:call-template>
    <xsl:variable name="safe"><xsl:call-template name="xyz"><xsl:with-param name="z" select="@safe_z"/></xsl:call-template></xsl:variable>
    <xsl:call-template name="block"><xsl:with-param name="text" select="concat('G0', $safe)"/></xsl:call-template>
  </xsl:template>
  <xsl:template name="z-block">
    <xsl:param name="g"/>
    <xsl:param name="z"/>
    <xsl:variable name="axes"><xsl:call-template name="xyz"><xsl:with-param name="z" select="$z"/></xsl:call-template></xsl:variable>
    <xsl:call-template name="block"><xsl:with-param name="text" select="concat($g, $axes)"/></xsl:call-template>
  </xsl:template>
  <xsl:template name="cycle-planes">
    <xsl:value-of select="concat(ext:format(ext:setup-z(@x, @y, @safe_z), 'length'), ',',
                                 ext:format(ext:setup-z(@x, @y, @r_z), 'length'), ',0,',
                                 ext:format(ext:setup-z(@x, @y, @bottom_z), 'length'), ',')"/>
  </xsl:template>

  <xsl:template match="DRILL_CYCLE">
    <xsl:call-template name="cycle-start"/>
    <xsl:variable name="planes"><xsl:call-template name="cycle-planes"/></xsl:variable>
    <xsl:choose>
      <xsl:when test="@dwell &gt; 0">
        <xsl:call-template name="block"><xsl:with-param name="text" select="concat('CYCLE82(', $planes, ',', ext:format(@dwell, 'dwell'), ')')"/></xsl:call-template>
      </xsl:when>
      <xsl:otherwise>
        <xsl:call-template name="block"><xsl:with-param name="text" select="concat('CYCLE81(', $planes, ')')"/></xsl:call-template>
      </xsl:otherwise>
    </xsl:choose>
    <xsl:value-of select="ext:moved-to(@x, @y, @safe_z)"/>
  </xsl:template>

  <!-- CYCLE83(RTP, RFP, SDIS, DP, DPR, FDEP, FDPR, DAM, DTB, DTS, FRF, VARI, _AXN, _MDEP, _VRT,
       _DTD, _DIS1): first depth FDEP = R plane - peck, degression DAM = peck (every further
       peck is DAM deep), VARI = 1 (swarf removal, back to the R plane, then rapid to _DIS1
       above the previous depth) or 0 (chip breaking, back off by _VRT). -->
  <xsl:template match="PECK_DRILL_CYCLE">
    <xsl:call-template name="cycle-start"/>
    <xsl:variable name="planes"><xsl:call-template name="cycle-planes"/></xsl:variable>
    <xsl:variable name="first" select="ext:format(ext:setup-z(@x, @y, @r_z - @peck), 'length')"/>
    <xsl:variable name="peck" select="ext:format(@peck, 'length')"/>
    <xsl:variable name="dwell">
      <xsl:choose><xsl:when test="@dwell &gt; 0"><xsl:value-of select="ext:format(@dwell, 'dwell')"/></xsl:when><xsl:otherwise>0</xsl:otherwise></xsl:choose>
    </xsl:variable>
    <xsl:variable name="tail">
      <xsl:choose>
        <xsl:when test="@peck_retract &gt; 0"><xsl:value-of select="concat('0,,,', ext:format(@peck_retract, 'length'), ',,')"/></xsl:when>
        <xsl:otherwise><xsl:value-of select="concat('1,,,,,', ext:format(@peck_clearance, 'length'))"/></xsl:otherwise>
      </xsl:choose>
    </xsl:variable>
    <xsl:call-template name="block">
      <xsl:with-param name="text" select="concat('CYCLE83(', $planes, ',', $first, ',,', $peck, ',', $dwell, ',0,1,', $tail, ')')"/>
    </xsl:call-template>
    <xsl:value-of select="ext:moved-to(@x, @y, @safe_z)"/>
  </xsl:template>

  <!-- CYCLE85(RTP, RFP, SDIS, DP, DPR, DTB, FFR, RFF): feed in and out at the cycle's feed. -->
  <xsl:template match="REAM_CYCLE | BORE_CYCLE[not(@spindle_stop = 'true')]">
    <xsl:call-template name="cycle-start"/>
    <xsl:variable name="planes"><xsl:call-template name="cycle-planes"/></xsl:variable>
    <xsl:variable name="dwell">
      <xsl:choose><xsl:when test="@dwell &gt; 0"><xsl:value-of select="ext:format(@dwell, 'dwell')"/></xsl:when><xsl:otherwise>0</xsl:otherwise></xsl:choose>
    </xsl:variable>
    <xsl:variable name="f" select="ext:format(@feed, 'feed')"/>
    <xsl:call-template name="block">
      <xsl:with-param name="text" select="concat('CYCLE85(', $planes, ',', $dwell, ',', $f, ',', $f, ')')"/>
    </xsl:call-template>
    <xsl:value-of select="ext:moved-to(@x, @y, @safe_z)"/>
  </xsl:template>

  <xsl:template match="TAP_CYCLE | BORE_CYCLE">
    <xsl:call-template name="cycle-start"/>
    <xsl:call-template name="z-block"><xsl:with-param name="g" select="'G0'"/><xsl:with-param name="z" select="@r_z"/></xsl:call-template>
    <xsl:call-template name="z-block"><xsl:with-param name="g" select="'G1'"/><xsl:with-param name="z" select="@bottom_z"/></xsl:call-template>
    <xsl:variable name="out"><xsl:choose><xsl:when test="@hand = 'left'">M3</xsl:when><xsl:otherwise>M4</xsl:otherwise></xsl:choose></xsl:variable>
    <xsl:variable name="in"><xsl:choose><xsl:when test="@hand = 'left'">M4</xsl:when><xsl:otherwise>M3</xsl:otherwise></xsl:choose></xsl:variable>
    <xsl:choose>
      <xsl:when test="self::TAP_CYCLE">
        <xsl:call-template name="block"><xsl:with-param name="text" select="'M5'"/></xsl:call-template>
        <xsl:call-template name="block"><xsl:with-param name="text" select="$out"/></xsl:call-template>
        <xsl:if test="@dwell &gt; 0">
          <xsl:call-template name="block"><xsl:with-param name="text" select="concat('G4 F', ext:format(@dwell, 'dwell'))"/></xsl:call-template>
        </xsl:if>
        <xsl:call-template name="z-block"><xsl:with-param name="g" select="'G1'"/><xsl:with-param name="z" select="@r_z"/></xsl:call-template>
        <xsl:call-template name="block"><xsl:with-param name="text" select="'M5'"/></xsl:call-template>
        <xsl:call-template name="block"><xsl:with-param name="text" select="$in"/></xsl:call-template>
        <xsl:call-template name="z-block"><xsl:with-param name="g" select="'G0'"/><xsl:with-param name="z" select="@safe_z"/></xsl:call-template>
      </xsl:when>
      <xsl:otherwise>
        <xsl:if test="@dwell &gt; 0">
          <xsl:call-template name="block"><xsl:with-param name="text" select="concat('G4 F', ext:format(@dwell, 'dwell'))"/></xsl:call-template>
        </xsl:if>
        <xsl:call-template name="block"><xsl:with-param name="text" select="'M5'"/></xsl:call-template>
        <xsl:call-template name="z-block"><xsl:with-param name="g" select="'G0'"/><xsl:with-param name="z" select="@safe_z"/></xsl:call-template>
        <xsl:call-template name="block"><xsl:with-param name="text" select="'M3'"/></xsl:call-template>
      </xsl:otherwise>
    </xsl:choose>
    <xsl:value-of select="ext:moved-to(@x, @y, @safe_z)"/>
  </xsl:template>

  <xsl:template match="PROGRAM_END">
    <xsl:call-template name="block"><xsl:with-param name="text" select="'M30'"/></xsl:call-template>
  </xsl:template>
</xsl:stylesheet>
