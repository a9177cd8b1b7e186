<?xml version="1.0" encoding="UTF-8"?>
<!-- Templates shared by the built-in profiles (docs/profiles.md). A profile imports this file
     and overrides what differs. The input is one chunk of the canonical program
     (engine/canon/canon.rng); state that must survive chunk boundaries (block numbers, modal
     words, the current position) lives in the job, through urn:ncpost:ext. -->
<xsl:stylesheet version="1.0" xmlns:xsl="http://www.w3.org/1999/XSL/Transform"
    xmlns:ext="urn:ncpost:ext" exclude-result-prefixes="ext">

  <!-- Set by the renderer. -->
  <xsl:param name="program_number" select="'1'"/>
  <xsl:param name="profile_id" select="''"/>
  <xsl:param name="arcs" select="'ijk'"/>
  <!-- The tool in the spindle when this chunk starts (0: none). -->
  <xsl:param name="tool" select="'0'"/>
  <!-- 'yes': every block starts with N and ext:block(). Profiles override it. -->
  <xsl:variable name="numbered" select="'no'"/>

  <xsl:template match="/chunk"><xsl:apply-templates select="*"/></xsl:template>
  <xsl:template match="text()"/>

  <!-- One block: optional N word, the line-length check, the newline. -->
  <xsl:template name="block">
    <xsl:param name="text"/>
    <xsl:choose>
      <xsl:when test="$numbered = 'yes'">
        <xsl:value-of select="ext:line(concat('N', ext:block(), ' ', $text))"/>
      </xsl:when>
      <xsl:otherwise><xsl:value-of select="ext:line($text)"/></xsl:otherwise>
    </xsl:choose>
    <xsl:text>&#10;</xsl:text>
  </xsl:template>

  <xsl:template name="comment-block">
    <xsl:param name="text"/>
    <xsl:call-template name="block">
      <xsl:with-param name="text" select="concat('(', ext:comment($text), ')')"/>
    </xsl:call-template>
  </xsl:template>

  <!-- " X.. Y.. Z.." of a point, through the machine set-up, plus rotary axes when present. -->
  <xsl:template name="xyz">
    <xsl:param name="x" select="@x"/>
    <xsl:param name="y" select="@y"/>
    <xsl:param name="z" select="@z"/>
    <xsl:value-of select="concat(' X', ext:format(ext:setup-x($x, $y, $z), 'length'),
                                 ' Y', ext:format(ext:setup-y($x, $y, $z), 'length'),
                                 ' Z', ext:format(ext:setup-z($x, $y, $z), 'length'))"/>
    <xsl:if test="@a"><xsl:value-of select="concat(' A', ext:format(@a, 'angle'))"/></xsl:if>
    <xsl:if test="@b"><xsl:value-of select="concat(' B', ext:format(@b, 'angle'))"/></xsl:if>
    <xsl:if test="@c"><xsl:value-of select="concat(' C', ext:format(@c, 'angle'))"/></xsl:if>
  </xsl:template>

  <!-- Structure -->
  <xsl:template match="USE_LENGTH_UNITS"><xsl:value-of select="ext:program-units(@units)"/></xsl:template>
  <xsl:template match="SETUP_BEGIN | WORKPLAN_BEGIN">
    <xsl:call-template name="comment-block">
      <xsl:with-param name="text" select="concat(substring-before(local-name(), '_BEGIN'), ' #', @id, ' ', @name)"/>
    </xsl:call-template>
  </xsl:template>
  <xsl:template match="workingstep">
    <xsl:if test="not(@continued = 'true')">
      <xsl:call-template name="comment-block">
        <xsl:with-param name="text" select="concat('WS #', @id, ' ', @name)"/>
      </xsl:call-template>
    </xsl:if>
    <xsl:apply-templates select="*"/>
  </xsl:template>
  <xsl:template match="SET_ORIGIN_OFFSETS | SET_FEED_REFERENCE | SETUP_END | WORKPLAN_END | WORKINGSTEP_END"/>

  <xsl:template match="SELECT_PLANE">
    <xsl:variable name="word" select="ext:modal('plane', substring('G17G19G18', 1 + 3 * (@plane = 'yz') + 6 * (@plane = 'xz'), 3))"/>
    <xsl:if test="$word != ''">
      <xsl:call-template name="block"><xsl:with-param name="text" select="$word"/></xsl:call-template>
    </xsl:if>
  </xsl:template>

  <!-- Motion. The hot templates (one run per motion) build their block as one string with
       select= expressions, without result-tree fragments (<xsl:variable> with content) and
       without calling "block" / "xyz" / "arc-centre" (a call with parameters costs about as
       much as the motion's ext: functions): they do what those templates do, inline. A profile
       that overrides "block", "xyz" or "arc-centre" therefore overrides the motion templates
       too (heidenhain-tnc640 does; fanuc-family.xsl overrides ARC_FEED for its R arcs).
       Motions with rotary axes (@a, @b, @c) take the general path through "xyz" (a straight
       motion with more attributes than x, y, z; an arc with @a, @b or @c). Coordinates are read
       once into numbers: number(@x) is what the ext: functions compute from @x. -->
  <xsl:template match="STRAIGHT_TRAVERSE">
    <xsl:choose>
      <xsl:when test="@*[4]">
        <xsl:call-template name="straight-general"><xsl:with-param name="g" select="'G0'"/></xsl:call-template>
      </xsl:when>
      <xsl:when test="$numbered = 'yes'">
        <xsl:variable name="x" select="number(@x)"/>
        <xsl:variable name="y" select="number(@y)"/>
        <xsl:variable name="z" select="number(@z)"/>
        <xsl:variable name="axes" select="concat(' X', ext:format(ext:setup-x($x, $y, $z), 'length'),
                       ' Y', ext:format(ext:setup-y($x, $y, $z), 'length'),
                       ' Z', ext:format(ext:setup-z($x, $y, $z), 'length'))"/>
        <xsl:value-of select="concat(ext:line(concat('N', ext:block(), ' G0', $axes)), '&#10;', ext:moved-to($x, $y, $z))"/>
      </xsl:when>
      <xsl:otherwise>
        <xsl:variable name="x" select="number(@x)"/>
        <xsl:variable name="y" select="number(@y)"/>
        <xsl:variable name="z" select="number(@z)"/>
        <xsl:value-of select="concat(ext:line(concat('G0 X', ext:format(ext:setup-x($x, $y, $z), 'length'),
                       ' Y', ext:format(ext:setup-y($x, $y, $z), 'length'),
                       ' Z', ext:format(ext:setup-z($x, $y, $z), 'length'))), '&#10;', ext:moved-to($x, $y, $z))"/>
      </xsl:otherwise>
    </xsl:choose>
  </xsl:template>
  <xsl:template match="STRAIGHT_FEED">
    <xsl:choose>
      <xsl:when test="@*[4]">
        <xsl:call-template name="straight-general"><xsl:with-param name="g" select="'G1'"/></xsl:call-template>
      </xsl:when>
      <xsl:when test="$numbered = 'yes'">
        <xsl:variable name="x" select="number(@x)"/>
        <xsl:variable name="y" select="number(@y)"/>
        <xsl:variable name="z" select="number(@z)"/>
        <xsl:variable name="axes" select="concat(' X', ext:format(ext:setup-x($x, $y, $z), 'length'),
                       ' Y', ext:format(ext:setup-y($x, $y, $z), 'length'),
                       ' Z', ext:format(ext:setup-z($x, $y, $z), 'length'))"/>
        <xsl:value-of select="concat(ext:line(concat('N', ext:block(), ' G1', $axes)), '&#10;', ext:moved-to($x, $y, $z))"/>
      </xsl:when>
      <xsl:otherwise>
        <xsl:variable name="x" select="number(@x)"/>
        <xsl:variable name="y" select="number(@y)"/>
        <xsl:variable name="z" select="number(@z)"/>
        <xsl:value-of select="concat(ext:line(concat('G1 X', ext:format(ext:setup-x($x, $y, $z), 'length'),
                       ' Y', ext:format(ext:setup-y($x, $y, $z), 'length'),
                       ' Z', ext:format(ext:setup-z($x, $y, $z), 'length'))), '&#10;', ext:moved-to($x, $y, $z))"/>
      </xsl:otherwise>
    </xsl:choose>
  </xsl:template>
  <!-- Through "xyz" and "block": motions with more than x, y, z (rotary axes, tool axis). -->
  <xsl:template name="straight-general">
    <xsl:param name="g"/>
    <xsl:variable name="axes"><xsl:call-template name="xyz"/></xsl:variable>
    <xsl:call-template name="block">
      <xsl:with-param name="text" select="concat($g, $axes)"/>
    </xsl:call-template>
    <xsl:value-of select="ext:moved-to(@x, @y, @z)"/>
  </xsl:template>

  <!-- The arc's centre as incremental I, J, K from its start (ext:position), in its plane. -->
  <xsl:template name="arc-ijk">
    <xsl:variable name="sx" select="ext:position('x')"/>
    <xsl:variable name="sy" select="ext:position('y')"/>
    <xsl:variable name="sz" select="ext:position('z')"/>
    <xsl:variable name="i" select="ext:format(ext:arc-i(ext:setup-x($sx, $sy, $sz), ext:setup-x(@cx, @cy, @cz)), 'length')"/>
    <xsl:variable name="j" select="ext:format(ext:arc-j(ext:setup-y($sx, $sy, $sz), ext:setup-y(@cx, @cy, @cz)), 'length')"/>
    <xsl:variable name="k" select="ext:format(ext:arc-k(ext:setup-z($sx, $sy, $sz), ext:setup-z(@cx, @cy, @cz)), 'length')"/>
    <xsl:choose>
      <xsl:when test="@plane = 'yz'"><xsl:value-of select="concat(' J', $j, ' K', $k)"/></xsl:when>
      <xsl:when test="@plane = 'xz'"><xsl:value-of select="concat(' I', $i, ' K', $k)"/></xsl:when>
      <xsl:otherwise><xsl:value-of select="concat(' I', $i, ' J', $j)"/></xsl:otherwise>
    </xsl:choose>
  </xsl:template>

  <xsl:template name="plane-word">
    <xsl:choose>
      <xsl:when test="@plane = 'yz'">G19</xsl:when>
      <xsl:when test="@plane = 'xz'">G18</xsl:when>
      <xsl:otherwise>G17</xsl:otherwise>
    </xsl:choose>
  </xsl:template>

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
    <xsl:choose>
      <xsl:when test="@a or @b or @c">
        <xsl:call-template name="arc-general"/>
      </xsl:when>
      <xsl:otherwise>
        <xsl:variable name="x" select="number(@x)"/>
        <xsl:variable name="y" select="number(@y)"/>
        <xsl:variable name="z" select="number(@z)"/>
        <xsl:variable name="cx" select="number(@cx)"/>
        <xsl:variable name="cy" select="number(@cy)"/>
        <xsl:variable name="cz" select="number(@cz)"/>
        <xsl:variable name="axes" select="concat(substring('G2G3', 1 + 2 * (@rotation &gt; 0), 2),
                       ' X', ext:format(ext:setup-x($x, $y, $z), 'length'),
                       ' Y', ext:format(ext:setup-y($x, $y, $z), 'length'),
                       ' Z', ext:format(ext:setup-z($x, $y, $z), 'length'))"/>
        <!-- arc-ijk, inline -->
        <xsl:variable name="sx" select="ext:position('x')"/>
        <xsl:variable name="sy" select="ext:position('y')"/>
        <xsl:variable name="sz" select="ext:position('z')"/>
        <xsl:variable name="text" select="concat($axes,
            substring(concat(' I', ext:format(ext:arc-i(ext:setup-x($sx, $sy, $sz), ext:setup-x($cx, $cy, $cz)), 'length')), 1, 1000 * ($pl != 1)),
            substring(concat(' J', ext:format(ext:arc-j(ext:setup-y($sx, $sy, $sz), ext:setup-y($cx, $cy, $cz)), 'length')), 1, 1000 * ($pl != 2)),
            substring(concat(' K', ext:format(ext:arc-k(ext:setup-z($sx, $sy, $sz), ext:setup-z($cx, $cy, $cz)), 'length')), 1, 1000 * ($pl != 0)),
            substring(concat(' P', translate(@rotation, '-', '')), 1, 1000 * (@rotation &gt; 1 or @rotation &lt; -1)))"/>
        <xsl:choose>
          <xsl:when test="$numbered = 'yes'">
            <xsl:value-of select="concat(ext:line(concat('N', ext:block(), ' ', $text)), '&#10;', ext:moved-to($x, $y, $z))"/>
          </xsl:when>
          <xsl:otherwise>
            <xsl:value-of select="concat(ext:line($text), '&#10;', ext:moved-to($x, $y, $z))"/>
          </xsl:otherwise>
        </xsl:choose>
      </xsl:otherwise>
    </xsl:choose>
  </xsl:template>

  <!-- G2/G3 through "xyz" and "arc-centre": arcs with rotary axes. -->
  <xsl:template name="arc-general">
    <xsl:variable name="g">
      <xsl:choose><xsl:when test="@rotation &gt; 0">G3</xsl:when><xsl:otherwise>G2</xsl:otherwise></xsl:choose>
    </xsl:variable>
    <xsl:variable name="axes"><xsl:call-template name="xyz"/></xsl:variable>
    <xsl:variable name="centre"><xsl:call-template name="arc-centre"/></xsl:variable>
    <xsl:variable name="turns">
      <xsl:if test="@rotation &gt; 1 or @rotation &lt; -1">
        <xsl:value-of select="concat(' P', translate(@rotation, '-', ''))"/>
      </xsl:if>
    </xsl:variable>
    <xsl:call-template name="block">
      <xsl:with-param name="text" select="concat($g, $axes, $centre, $turns)"/>
    </xsl:call-template>
    <xsl:value-of select="ext:moved-to(@x, @y, @z)"/>
  </xsl:template>

  <!-- IJK by default; profiles with arcs 'r' override it. -->
  <xsl:template name="arc-centre"><xsl:call-template name="arc-ijk"/></xsl:template>

  <xsl:template match="NURBS_FEED">
    <xsl:message terminate="yes">NURBS_FEED: this profile needs capabilities.nurbs = linearize</xsl:message>
  </xsl:template>

  <!-- Feed, spindle, tools, coolant -->
  <xsl:template match="SET_FEED_RATE">
    <xsl:call-template name="block"><xsl:with-param name="text" select="concat('F', ext:format(@rate, 'feed'))"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="SET_SPINDLE_SPEED">
    <xsl:call-template name="block"><xsl:with-param name="text" select="concat('S', ext:format(@rpm, 'speed'))"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="START_SPINDLE_CLOCKWISE">
    <xsl:call-template name="block"><xsl:with-param name="text" select="'M3'"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="START_SPINDLE_COUNTERCLOCKWISE">
    <xsl:call-template name="block"><xsl:with-param name="text" select="'M4'"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="STOP_SPINDLE_TURNING">
    <xsl:call-template name="block"><xsl:with-param name="text" select="'M5'"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="SPINDLE_RETRACT"/>
  <!-- Each call on its own (a chunk boundary may fall between them): T.., then T.. M6. -->
  <xsl:template match="SELECT_TOOL">
    <xsl:call-template name="block"><xsl:with-param name="text" select="concat('T', @slot)"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="CHANGE_TOOL">
    <xsl:call-template name="block"><xsl:with-param name="text" select="concat('T', @slot, ' M6')"/></xsl:call-template>
  </xsl:template>
  <!-- The tool in the spindle: the last CHANGE_TOOL of this chunk, or the renderer's $tool. -->
  <xsl:template name="current-tool">
    <xsl:choose>
      <xsl:when test="preceding::CHANGE_TOOL"><xsl:value-of select="preceding::CHANGE_TOOL[1]/@slot"/></xsl:when>
      <xsl:otherwise><xsl:value-of select="$tool"/></xsl:otherwise>
    </xsl:choose>
  </xsl:template>
  <xsl:template match="USE_TOOL_LENGTH_OFFSET">
    <xsl:variable name="tool"><xsl:call-template name="current-tool"/></xsl:variable>
    <xsl:choose>
      <xsl:when test="@length = 0">
        <xsl:call-template name="block"><xsl:with-param name="text" select="'G49'"/></xsl:call-template>
      </xsl:when>
      <xsl:when test="$tool != '0'">
        <xsl:call-template name="block"><xsl:with-param name="text" select="concat('G43 H', $tool)"/></xsl:call-template>
      </xsl:when>
      <xsl:otherwise>
        <xsl:call-template name="block"><xsl:with-param name="text" select="'G43'"/></xsl:call-template>
      </xsl:otherwise>
    </xsl:choose>
  </xsl:template>
  <xsl:template match="FLOOD_ON">
    <xsl:call-template name="block"><xsl:with-param name="text" select="'M8'"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="MIST_ON">
    <xsl:call-template name="block"><xsl:with-param name="text" select="'M7'"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="FLOOD_OFF | MIST_OFF">
    <xsl:call-template name="block"><xsl:with-param name="text" select="'M9'"/></xsl:call-template>
  </xsl:template>

  <!-- Other -->
  <xsl:template match="DWELL">
    <xsl:call-template name="block"><xsl:with-param name="text" select="concat('G4 P', ext:format(@seconds, 'dwell'))"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="COMMENT">
    <xsl:call-template name="comment-block"><xsl:with-param name="text" select="string(.)"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="MESSAGE">
    <xsl:call-template name="comment-block"><xsl:with-param name="text" select="concat('MSG ', string(.))"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="OPTIONAL_PROGRAM_STOP">
    <xsl:call-template name="block"><xsl:with-param name="text" select="'M1'"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="PROGRAM_STOP">
    <xsl:call-template name="block"><xsl:with-param name="text" select="'M0'"/></xsl:call-template>
  </xsl:template>

  <xsl:template match="DRILL_CYCLE | PECK_DRILL_CYCLE | TAP_CYCLE | BORE_CYCLE | REAM_CYCLE">
    <xsl:message terminate="yes">this profile has no native cycles: set capabilities.canned_cycles to expand</xsl:message>
  </xsl:template>
</xsl:stylesheet>
