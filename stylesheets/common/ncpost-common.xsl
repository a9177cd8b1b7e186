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
  <!-- Five-axis profiles (profile.json kinematics, docs/kinematics.md): the rotary addresses
       the motions carry ('AC', 'BC', ...; all three otherwise) and whether the control keeps
       the tool tip on the programmed point ('yes': TRAORI, G43.4, M128). -->
  <xsl:param name="rotary_axes" select="'ABC'"/>
  <xsl:param name="tcp" select="'no'"/>
  <!-- 'yes' when every block starts with N and a block number: the profile's
       block_numbers.numbered (profile.json). ext:block-line() follows it, or the
       block_numbers="on|off" output option of the enclosing <workingstep> where one is set
       (ext:block-numbering() called at a node inside a workingstep says which). -->
  <xsl:variable name="numbered" select="ext:block-numbering()"/>

  <xsl:template match="/chunk"><xsl:apply-templates select="*"/></xsl:template>
  <xsl:template match="text()"/>

  <!-- One block: the N word when the profile numbers blocks, the line-length check, the
       newline. -->
  <xsl:template name="block">
    <xsl:param name="text"/>
    <xsl:value-of select="ext:block-line($text)"/>
    <xsl:text>&#10;</xsl:text>
  </xsl:template>

  <xsl:template name="comment-block">
    <xsl:param name="text"/>
    <xsl:call-template name="block">
      <xsl:with-param name="text" select="concat('(', ext:comment($text), ')')"/>
    </xsl:call-template>
  </xsl:template>

  <!-- " X.. Y.. Z.." of a point, through the machine set-up, plus the machine's rotary axes
       when present. -->
  <xsl:template name="xyz">
    <xsl:param name="x" select="@x"/>
    <xsl:param name="y" select="@y"/>
    <xsl:param name="z" select="@z"/>
    <xsl:value-of select="concat(' X', ext:format(ext:setup-x($x, $y, $z), 'length'),
                                 ' Y', ext:format(ext:setup-y($x, $y, $z), 'length'),
                                 ' Z', ext:format(ext:setup-z($x, $y, $z), 'length'))"/>
    <xsl:if test="@a and contains($rotary_axes, 'A')"><xsl:value-of select="concat(' A', ext:format(@a, 'angle'))"/></xsl:if>
    <xsl:if test="@b and contains($rotary_axes, 'B')"><xsl:value-of select="concat(' B', ext:format(@b, 'angle'))"/></xsl:if>
    <xsl:if test="@c and contains($rotary_axes, 'C')"><xsl:value-of select="concat(' C', ext:format(@c, 'angle'))"/></xsl:if>
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
      <xsl:value-of select="ext:block-line($word)"/><xsl:text>&#10;</xsl:text>
    </xsl:if>
  </xsl:template>

  <!-- Motion. These run once per motion, which makes them most of a post's time, so each is
       two extension calls: ext:motion-words() (X Y Z, and A B C when present, through the
       machine set-up and the length/angle formats; it also records the end as the current
       position) or ext:arc-words(), then ext:block-line() (N word, line-length check). They call no named
       template: a profile that wants other words overrides these templates themselves
       (heidenhain-tnc640 does), not "xyz" or "block". docs/xslt-extensions.md, "Words". -->
  <xsl:template match="STRAIGHT_TRAVERSE">
    <xsl:value-of select="ext:block-line(concat('G0', ext:motion-words()))"/>
    <xsl:text>&#10;</xsl:text>
  </xsl:template>
  <xsl:template match="STRAIGHT_FEED">
    <xsl:value-of select="ext:block-line(concat('G1', ext:motion-words()))"/>
    <xsl:text>&#10;</xsl:text>
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

  <!-- A run of motions (profile.json render.motion_runs): the blocks the three templates
       around this one write for each motion, written by the engine from memory in one call
       (docs/render.md, "Motion runs"). -->
  <xsl:template match="motions">
    <xsl:value-of select="ext:motion-run('G0', 'G1', 'G2', 'G3', $arc_form)"/>
  </xsl:template>

  <!-- G2/G3 with its plane's G17/G19/G18 first when the plane changed. $arc_form is 'ijk';
       the FANUC family sets it to the profile's $arcs, for R where R can say the arc. -->
  <xsl:variable name="arc_form" select="'ijk'"/>
  <xsl:template match="ARC_FEED">
    <xsl:if test="not(@plane)">
      <xsl:message terminate="yes">ARC_FEED in a tilted plane has no G2/G3 form on this controller</xsl:message>
    </xsl:if>
    <xsl:variable name="plane" select="ext:modal('plane', substring('G17G19G18', 1 + 3 * ((@plane = 'yz') + 2 * (@plane = 'xz')), 3))"/>
    <xsl:if test="$plane != ''">
      <xsl:value-of select="ext:block-line($plane)"/><xsl:text>&#10;</xsl:text>
    </xsl:if>
    <xsl:value-of select="ext:block-line(concat(substring('G2G3', 1 + 2 * (@rotation &gt; 0), 2), ext:arc-words($arc_form)))"/>
    <xsl:text>&#10;</xsl:text>
  </xsl:template>

  <xsl:template match="NURBS_FEED">
    <xsl:message terminate="yes">NURBS_FEED: this profile needs capabilities.nurbs = linearize</xsl:message>
  </xsl:template>

  <!-- Feed, spindle, tools, coolant -->
  <xsl:template match="SET_FEED_RATE">
    <xsl:value-of select="ext:block-line(concat('F', ext:format(@rate, 'feed')))"/><xsl:text>&#10;</xsl:text>
  </xsl:template>
  <xsl:template match="SET_SPINDLE_SPEED">
    <xsl:value-of select="ext:block-line(concat('S', ext:format(@rpm, 'speed')))"/><xsl:text>&#10;</xsl:text>
  </xsl:template>
  <xsl:template match="START_SPINDLE_CLOCKWISE">
    <xsl:value-of select="ext:block-line('M3')"/><xsl:text>&#10;</xsl:text>
  </xsl:template>
  <xsl:template match="START_SPINDLE_COUNTERCLOCKWISE">
    <xsl:value-of select="ext:block-line('M4')"/><xsl:text>&#10;</xsl:text>
  </xsl:template>
  <xsl:template match="STOP_SPINDLE_TURNING">
    <xsl:value-of select="ext:block-line('M5')"/><xsl:text>&#10;</xsl:text>
  </xsl:template>
  <xsl:template match="SPINDLE_RETRACT"/>
  <!-- Each call on its own (a chunk boundary may fall between them): T.., then T.. M6. -->
  <xsl:template match="SELECT_TOOL">
    <xsl:value-of select="ext:block-line(concat('T', @slot))"/><xsl:text>&#10;</xsl:text>
  </xsl:template>
  <xsl:template match="CHANGE_TOOL">
    <xsl:value-of select="ext:block-line(concat('T', @slot, ' M6'))"/><xsl:text>&#10;</xsl:text>
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
        <xsl:value-of select="ext:block-line('G49')"/><xsl:text>&#10;</xsl:text>
      </xsl:when>
      <xsl:when test="$tool != '0'">
        <xsl:value-of select="ext:block-line(concat('G43 H', $tool))"/><xsl:text>&#10;</xsl:text>
      </xsl:when>
      <xsl:otherwise>
        <xsl:value-of select="ext:block-line('G43')"/><xsl:text>&#10;</xsl:text>
      </xsl:otherwise>
    </xsl:choose>
  </xsl:template>
  <xsl:template match="FLOOD_ON">
    <xsl:value-of select="ext:block-line('M8')"/><xsl:text>&#10;</xsl:text>
  </xsl:template>
  <xsl:template match="MIST_ON">
    <xsl:value-of select="ext:block-line('M7')"/><xsl:text>&#10;</xsl:text>
  </xsl:template>
  <xsl:template match="FLOOD_OFF | MIST_OFF">
    <xsl:value-of select="ext:block-line('M9')"/><xsl:text>&#10;</xsl:text>
  </xsl:template>

  <!-- Other -->
  <xsl:template match="DWELL">
    <xsl:value-of select="ext:block-line(concat('G4 P', ext:format(@seconds, 'dwell')))"/><xsl:text>&#10;</xsl:text>
  </xsl:template>
  <xsl:template match="COMMENT">
    <xsl:call-template name="comment-block"><xsl:with-param name="text" select="string(.)"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="MESSAGE">
    <xsl:call-template name="comment-block"><xsl:with-param name="text" select="concat('MSG ', string(.))"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="OPTIONAL_PROGRAM_STOP">
    <xsl:value-of select="ext:block-line('M1')"/><xsl:text>&#10;</xsl:text>
  </xsl:template>
  <xsl:template match="PROGRAM_STOP">
    <xsl:value-of select="ext:block-line('M0')"/><xsl:text>&#10;</xsl:text>
  </xsl:template>

  <xsl:template match="DRILL_CYCLE | PECK_DRILL_CYCLE | TAP_CYCLE | BORE_CYCLE | REAM_CYCLE">
    <xsl:message terminate="yes">this profile has no native cycles: set capabilities.canned_cycles to expand</xsl:message>
  </xsl:template>
</xsl:stylesheet>
