<?xml version="1.0" encoding="UTF-8"?>
<!-- KUKA KR C4 robot carrying a milling spindle: one KRL .src module, DEF NAME() ... END.
     Positions are written inline ({X, Y, Z, A, B, C} frames), so no .dat file is needed: the
     program streams chunk by chunk and a .dat would have to list every point before the first
     motion (docs/profiles.md, kuka-krl). The robot's frames, outputs and speeds below are the
     cell's; change them here for another cell. -->
<xsl:stylesheet version="1.0" xmlns:xsl="http://www.w3.org/1999/XSL/Transform"
    xmlns:ext="urn:ncpost:ext" xmlns:math="http://exslt.org/math"
    exclude-result-prefixes="ext math">
  <xsl:output method="text" encoding="UTF-8"/>

  <xsl:param name="program_number" select="'1'"/>
  <xsl:param name="profile_id" select="''"/>
  <xsl:param name="arcs" select="'ijk'"/>
  <xsl:param name="tool" select="'0'"/>

  <!-- The cell. BASE_DATA[n] is the workpiece frame taught on the robot; TOOL_DATA[n] the
       spindle nose (its Z along the tool, pointing out of the spindle); the tool length of
       USE_TOOL_LENGTH_OFFSET is added along that Z. -->
  <xsl:variable name="base_index" select="1"/>
  <xsl:variable name="tool_index" select="1"/>
  <!-- Orientation of the tool frame in the base frame when the tool axis is +Z (tool pointing
       down): ZYX Euler angles A, B, C in degrees. -->
  <xsl:variable name="down_a" select="0"/>
  <xsl:variable name="down_b" select="0"/>
  <xsl:variable name="down_c" select="180"/>
  <!-- Rapid traverse along the path, m/s; approximation distance (C_DIS), mm. -->
  <xsl:variable name="rapid_velocity" select="0.5"/>
  <xsl:variable name="cdis" select="0.05"/>
  <!-- Digital outputs of the spindle and coolant ($OUT[n]); the spindle speed goes to an
       analogue output scaled to the spindle's maximum. -->
  <xsl:variable name="out_spindle_cw" select="1"/>
  <xsl:variable name="out_spindle_ccw" select="2"/>
  <xsl:variable name="out_flood" select="3"/>
  <xsl:variable name="out_mist" select="4"/>
  <xsl:variable name="anout_speed" select="1"/>
  <xsl:variable name="max_spindle_rpm" select="24000"/>
  <!-- Helices have no KRL form (CIRC is a plane circle): they become LIN points within this
       chord deviation, mm. -->
  <xsl:variable name="chord" select="0.001"/>

  <xsl:template match="/chunk"><xsl:apply-templates select="*"/></xsl:template>
  <xsl:template match="text()"/>

  <xsl:template name="line">
    <xsl:param name="text"/>
    <xsl:value-of select="ext:line($text)"/>
    <xsl:text>&#10;</xsl:text>
  </xsl:template>
  <xsl:template name="comment">
    <xsl:param name="text"/>
    <xsl:call-template name="line"><xsl:with-param name="text" select="concat('; ', ext:comment($text))"/></xsl:call-template>
  </xsl:template>

  <!-- A KRL name: letters, digits and _, starting with a letter, at most 24 characters. -->
  <xsl:template name="program-name">
    <xsl:param name="name"/>
    <xsl:variable name="keep" select="'ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_'"/>
    <xsl:variable name="clean" select="translate($name, translate($name, $keep, ''), '________________________________________')"/>
    <xsl:variable name="lettered">
      <xsl:choose>
        <xsl:when test="$clean = ''"><xsl:value-of select="concat('NCPOST', $program_number)"/></xsl:when>
        <xsl:when test="contains('ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz', substring($clean, 1, 1))"><xsl:value-of select="$clean"/></xsl:when>
        <xsl:otherwise><xsl:value-of select="concat('P', $clean)"/></xsl:otherwise>
      </xsl:choose>
    </xsl:variable>
    <xsl:value-of select="substring($lettered, 1, 24)"/>
  </xsl:template>

  <!-- "A .., B .., C .." for the tool axis (i, j, k) (program axes; +Z when absent). The tool
       frame's Z points into the work, against the axis: with A = 0, C = atan2(j', -sqrt(1 - j'^2))
       and B = atan2(i', k'), (i', j', k') the axis through the set-up. -->
  <xsl:template name="abc">
    <xsl:param name="i" select="@i"/>
    <xsl:param name="j" select="@j"/>
    <xsl:param name="k" select="@k"/>
    <xsl:choose>
      <xsl:when test="string($i) = '' or ($i = 0 and $j = 0 and $k &gt; 0 and ext:setup-k(0, 0, 1) &gt; 0.9999999999)">
        <xsl:value-of select="concat('A ', ext:format($down_a, 'angle'), ', B ', ext:format($down_b, 'angle'), ', C ', ext:format($down_c, 'angle'))"/>
      </xsl:when>
      <xsl:otherwise>
        <xsl:variable name="n" select="math:sqrt($i * $i + $j * $j + $k * $k)"/>
        <xsl:variable name="ii" select="ext:setup-i($i, $j, $k) div $n"/>
        <xsl:variable name="jj" select="ext:setup-j($i, $j, $k) div $n"/>
        <xsl:variable name="kk" select="ext:setup-k($i, $j, $k) div $n"/>
        <xsl:variable name="deg" select="180 div math:constant('PI', 20)"/>
        <xsl:value-of select="concat('A 0, B ', ext:format(math:atan2($ii, $kk) * $deg, 'angle'),
                                     ', C ', ext:format(math:atan2($jj, -math:sqrt(1 - $jj * $jj)) * $deg, 'angle'))"/>
      </xsl:otherwise>
    </xsl:choose>
  </xsl:template>

  <!-- "{X .., Y .., Z .., A .., B .., C ..}" of a program point, through the set-up. -->
  <xsl:template name="frame">
    <xsl:param name="x"/>
    <xsl:param name="y"/>
    <xsl:param name="z"/>
    <xsl:param name="abc"/>
    <xsl:value-of select="concat('{X ', ext:format(ext:setup-x($x, $y, $z), 'length'),
                                 ', Y ', ext:format(ext:setup-y($x, $y, $z), 'length'),
                                 ', Z ', ext:format(ext:setup-z($x, $y, $z), 'length'),
                                 ', ', $abc, '}')"/>
  </xsl:template>

  <!-- Path velocity: V_RAPID or V_FEED, assigned only when it changes. -->
  <xsl:template name="velocity">
    <xsl:param name="which"/>
    <xsl:variable name="word" select="ext:modal('velocity', $which)"/>
    <xsl:if test="$word != ''">
      <xsl:call-template name="line"><xsl:with-param name="text" select="concat('$VEL.CP = ', $word)"/></xsl:call-template>
    </xsl:if>
  </xsl:template>

  <!-- Structure -->
  <xsl:template match="PROJECT_BEGIN">
    <xsl:variable name="name"><xsl:call-template name="program-name"><xsl:with-param name="name" select="@name"/></xsl:call-template></xsl:variable>
    <xsl:call-template name="line"><xsl:with-param name="text" select="'&amp;ACCESS RVP'"/></xsl:call-template>
    <xsl:call-template name="line"><xsl:with-param name="text" select="'&amp;REL 1'"/></xsl:call-template>
    <xsl:call-template name="line"><xsl:with-param name="text" select="concat('DEF ', $name, '()')"/></xsl:call-template>
    <xsl:call-template name="line"><xsl:with-param name="text" select="'DECL REAL V_RAPID, V_FEED'"/></xsl:call-template>
    <xsl:call-template name="comment"><xsl:with-param name="text" select="concat('PROJECT #', @id, ' ', @name)"/></xsl:call-template>
    <xsl:call-template name="comment"><xsl:with-param name="text" select="concat('ncpost profile ', $profile_id, ' - save as ', $name, '.src')"/></xsl:call-template>
    <xsl:call-template name="line"><xsl:with-param name="text" select="';FOLD INI'"/></xsl:call-template>
    <xsl:call-template name="line"><xsl:with-param name="text" select="'BAS(#INITMOV, 0)'"/></xsl:call-template>
    <xsl:call-template name="line"><xsl:with-param name="text" select="';ENDFOLD (INI)'"/></xsl:call-template>
    <xsl:call-template name="line"><xsl:with-param name="text" select="concat('$BASE = BASE_DATA[', $base_index, ']')"/></xsl:call-template>
    <xsl:call-template name="line"><xsl:with-param name="text" select="concat('$TOOL = TOOL_DATA[', $tool_index, ']')"/></xsl:call-template>
    <xsl:call-template name="line"><xsl:with-param name="text" select="'$ORI_TYPE = #CONSTANT'"/></xsl:call-template>
    <xsl:call-template name="line"><xsl:with-param name="text" select="'$CIRC_TYPE = #BASE'"/></xsl:call-template>
    <xsl:call-template name="line"><xsl:with-param name="text" select="concat('$APO.CDIS = ', ext:format($cdis, 'length'))"/></xsl:call-template>
    <xsl:call-template name="line"><xsl:with-param name="text" select="concat('V_RAPID = ', $rapid_velocity)"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="USE_LENGTH_UNITS"><xsl:value-of select="ext:program-units(@units)"/></xsl:template>
  <xsl:template match="SETUP_BEGIN | WORKPLAN_BEGIN">
    <xsl:call-template name="comment">
      <xsl:with-param name="text" select="concat(substring-before(local-name(), '_BEGIN'), ' #', @id, ' ', @name)"/>
    </xsl:call-template>
  </xsl:template>
  <xsl:template match="workingstep">
    <xsl:if test="not(@continued = 'true')">
      <xsl:call-template name="comment"><xsl:with-param name="text" select="concat('WS #', @id, ' ', @name)"/></xsl:call-template>
    </xsl:if>
    <xsl:apply-templates select="*"/>
  </xsl:template>
  <xsl:template match="SET_ORIGIN_OFFSETS | SET_FEED_REFERENCE | SETUP_END | WORKPLAN_END | WORKINGSTEP_END | SELECT_PLANE | SELECT_TOOL"/>
  <xsl:template match="COMMENT">
    <xsl:call-template name="comment"><xsl:with-param name="text" select="."/></xsl:call-template>
  </xsl:template>
  <!-- KRL messages need the message system's structures (MsgNotify); a comment is enough for
       the operator reading the program. -->
  <xsl:template match="MESSAGE">
    <xsl:call-template name="comment"><xsl:with-param name="text" select="concat('MSG ', .)"/></xsl:call-template>
  </xsl:template>

  <!-- Motion. The first motion of the program is PTP (the robot may stand anywhere, and only a
       PTP may start from an unknown configuration); every later traverse is a LIN at V_RAPID,
       because a PTP near the part leaves the straight line. -->
  <xsl:template match="STRAIGHT_TRAVERSE | STRAIGHT_FEED">
    <xsl:variable name="abc"><xsl:call-template name="abc"/></xsl:variable>
    <xsl:variable name="frame">
      <xsl:call-template name="frame">
        <xsl:with-param name="x" select="@x"/><xsl:with-param name="y" select="@y"/><xsl:with-param name="z" select="@z"/>
        <xsl:with-param name="abc" select="$abc"/>
      </xsl:call-template>
    </xsl:variable>
    <xsl:choose>
      <xsl:when test="ext:modal('first-motion', 'done') != ''">
        <xsl:if test="self::STRAIGHT_FEED">
          <xsl:message terminate="yes">the program's first motion is a feed: a robot must reach its start with a traverse (PTP)</xsl:message>
        </xsl:if>
        <xsl:call-template name="line"><xsl:with-param name="text" select="concat('PTP ', $frame)"/></xsl:call-template>
      </xsl:when>
      <xsl:otherwise>
        <xsl:call-template name="velocity">
          <xsl:with-param name="which"><xsl:choose><xsl:when test="self::STRAIGHT_TRAVERSE">V_RAPID</xsl:when><xsl:otherwise>V_FEED</xsl:otherwise></xsl:choose></xsl:with-param>
        </xsl:call-template>
        <xsl:call-template name="line"><xsl:with-param name="text" select="concat('LIN ', $frame, ' C_DIS')"/></xsl:call-template>
      </xsl:otherwise>
    </xsl:choose>
    <xsl:value-of select="ext:moved-to(@x, @y, @z)"/>
  </xsl:template>

  <!-- Arcs in the XY, YZ or XZ plane, in the plane's own coordinates (f, s) with the axis
       coordinate a (rs274's first, second, axis). A plane arc becomes CIRC pieces of at most
       180 degrees, each through the mid-point of its piece (a full circle is two pieces); a
       helix becomes LIN points. -->
  <xsl:template match="ARC_FEED">
    <xsl:if test="not(@plane)">
      <xsl:message terminate="yes">ARC_FEED in a tilted plane: not supported by this profile</xsl:message>
    </xsl:if>
    <xsl:variable name="plane" select="@plane"/>
    <xsl:variable name="abc"><xsl:call-template name="abc"/></xsl:variable>
    <xsl:variable name="px" select="ext:position('x')"/>
    <xsl:variable name="py" select="ext:position('y')"/>
    <xsl:variable name="pz" select="ext:position('z')"/>
    <xsl:variable name="sf" select="($plane = 'xy') * $px + ($plane = 'yz') * $py + ($plane = 'xz') * $pz"/>
    <xsl:variable name="ss" select="($plane = 'xy') * $py + ($plane = 'yz') * $pz + ($plane = 'xz') * $px"/>
    <xsl:variable name="sa" select="($plane = 'xy') * $pz + ($plane = 'yz') * $px + ($plane = 'xz') * $py"/>
    <xsl:variable name="cf" select="@first_axis"/>
    <xsl:variable name="cs" select="@second_axis"/>
    <xsl:variable name="rotation" select="@rotation"/>
    <xsl:call-template name="velocity"><xsl:with-param name="which" select="'V_FEED'"/></xsl:call-template>
    <xsl:choose>
      <xsl:when test="@axis_end_point - $sa &gt; 0.000000001 or $sa - @axis_end_point &gt; 0.000000001">
        <xsl:variable name="r" select="math:sqrt(($sf - $cf) * ($sf - $cf) + ($ss - $cs) * ($ss - $cs))"/>
        <xsl:variable name="step">
          <xsl:choose>
            <xsl:when test="$r &lt;= $chord * 2">90</xsl:when>
            <xsl:otherwise><xsl:value-of select="2 * math:acos(1 - $chord div $r) * 180 div math:constant('PI', 20)"/></xsl:otherwise>
          </xsl:choose>
        </xsl:variable>
        <xsl:for-each select="ext:arc-split($sf, $ss, $sa, @first_end, @second_end, @axis_end_point, $cf, $cs, $rotation, $step)">
          <xsl:variable name="x" select="($plane = 'xy') * @x + ($plane = 'yz') * @z + ($plane = 'xz') * @y"/>
          <xsl:variable name="y" select="($plane = 'xy') * @y + ($plane = 'yz') * @x + ($plane = 'xz') * @z"/>
          <xsl:variable name="z" select="($plane = 'xy') * @z + ($plane = 'yz') * @y + ($plane = 'xz') * @x"/>
          <xsl:variable name="frame">
            <xsl:call-template name="frame">
              <xsl:with-param name="x" select="$x"/><xsl:with-param name="y" select="$y"/><xsl:with-param name="z" select="$z"/>
              <xsl:with-param name="abc" select="$abc"/>
            </xsl:call-template>
          </xsl:variable>
          <xsl:call-template name="line"><xsl:with-param name="text" select="concat('LIN ', $frame, ' C_DIS')"/></xsl:call-template>
        </xsl:for-each>
      </xsl:when>
      <xsl:otherwise>
        <xsl:variable name="sign"><xsl:choose><xsl:when test="$rotation &gt; 0">1</xsl:when><xsl:otherwise>-1</xsl:otherwise></xsl:choose></xsl:variable>
        <xsl:for-each select="ext:arc-split($sf, $ss, $sa, @first_end, @second_end, @axis_end_point, $cf, $cs, $rotation, 180)">
          <!-- This piece starts where the previous one ended (program axes, ext:position). -->
          <xsl:variable name="qx" select="ext:position('x')"/>
          <xsl:variable name="qy" select="ext:position('y')"/>
          <xsl:variable name="qz" select="ext:position('z')"/>
          <xsl:variable name="qf" select="($plane = 'xy') * $qx + ($plane = 'yz') * $qy + ($plane = 'xz') * $qz"/>
          <xsl:variable name="qs" select="($plane = 'xy') * $qy + ($plane = 'yz') * $qz + ($plane = 'xz') * $qx"/>
          <xsl:variable name="half" select="ext:arc-sweep($qf, $qs, @x, @y, $cf, $cs, $sign) * $sign div 2"/>
          <xsl:variable name="mid" select="ext:arc-split($qf, $qs, @z, @x, @y, @z, $cf, $cs, $sign, $half * 1.000001)[1]"/>
          <xsl:variable name="aux">
            <xsl:call-template name="frame">
              <xsl:with-param name="x" select="($plane = 'xy') * $mid/@x + ($plane = 'yz') * $mid/@z + ($plane = 'xz') * $mid/@y"/>
              <xsl:with-param name="y" select="($plane = 'xy') * $mid/@y + ($plane = 'yz') * $mid/@x + ($plane = 'xz') * $mid/@z"/>
              <xsl:with-param name="z" select="($plane = 'xy') * $mid/@z + ($plane = 'yz') * $mid/@y + ($plane = 'xz') * $mid/@x"/>
              <xsl:with-param name="abc" select="$abc"/>
            </xsl:call-template>
          </xsl:variable>
          <xsl:variable name="x" select="($plane = 'xy') * @x + ($plane = 'yz') * @z + ($plane = 'xz') * @y"/>
          <xsl:variable name="y" select="($plane = 'xy') * @y + ($plane = 'yz') * @x + ($plane = 'xz') * @z"/>
          <xsl:variable name="z" select="($plane = 'xy') * @z + ($plane = 'yz') * @y + ($plane = 'xz') * @x"/>
          <xsl:variable name="end">
            <xsl:call-template name="frame">
              <xsl:with-param name="x" select="$x"/><xsl:with-param name="y" select="$y"/><xsl:with-param name="z" select="$z"/>
              <xsl:with-param name="abc" select="$abc"/>
            </xsl:call-template>
          </xsl:variable>
          <xsl:call-template name="line"><xsl:with-param name="text" select="concat('CIRC ', $aux, ', ', $end, ' C_DIS')"/></xsl:call-template>
          <xsl:value-of select="ext:moved-to($x, $y, $z)"/>
        </xsl:for-each>
      </xsl:otherwise>
    </xsl:choose>
    <xsl:value-of select="ext:moved-to(@x, @y, @z)"/>
  </xsl:template>

  <!-- Technology -->
  <xsl:template match="SET_FEED_RATE">
    <xsl:call-template name="line"><xsl:with-param name="text" select="concat('V_FEED = ', ext:format(@rate, 'feed'), ' ; ', ext:format(@rate * 1, 'length'), ' mm/min')"/></xsl:call-template>
    <!-- The next feed motion assigns $VEL.CP again. -->
    <xsl:value-of select="ext:modal-reset('velocity')"/>
  </xsl:template>
  <xsl:template match="SET_SPINDLE_SPEED">
    <xsl:call-template name="line">
      <xsl:with-param name="text" select="concat('$ANOUT[', $anout_speed, '] = ', format-number(@rpm div $max_spindle_rpm, '0.0####'), ' ; S', ext:format(@rpm, 'speed'), ' rpm')"/>
    </xsl:call-template>
  </xsl:template>
  <xsl:template match="START_SPINDLE_CLOCKWISE">
    <xsl:call-template name="line"><xsl:with-param name="text" select="concat('$OUT[', $out_spindle_ccw, '] = FALSE')"/></xsl:call-template>
    <xsl:call-template name="line"><xsl:with-param name="text" select="concat('$OUT[', $out_spindle_cw, '] = TRUE ; spindle clockwise')"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="START_SPINDLE_COUNTERCLOCKWISE">
    <xsl:call-template name="line"><xsl:with-param name="text" select="concat('$OUT[', $out_spindle_cw, '] = FALSE')"/></xsl:call-template>
    <xsl:call-template name="line"><xsl:with-param name="text" select="concat('$OUT[', $out_spindle_ccw, '] = TRUE ; spindle counter-clockwise')"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="STOP_SPINDLE_TURNING">
    <xsl:call-template name="line"><xsl:with-param name="text" select="concat('$OUT[', $out_spindle_cw, '] = FALSE')"/></xsl:call-template>
    <xsl:call-template name="line"><xsl:with-param name="text" select="concat('$OUT[', $out_spindle_ccw, '] = FALSE ; spindle stop')"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="FLOOD_ON">
    <xsl:call-template name="line"><xsl:with-param name="text" select="concat('$OUT[', $out_flood, '] = TRUE ; flood coolant')"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="MIST_ON">
    <xsl:call-template name="line"><xsl:with-param name="text" select="concat('$OUT[', $out_mist, '] = TRUE ; mist coolant')"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="FLOOD_OFF | MIST_OFF">
    <xsl:call-template name="line"><xsl:with-param name="text" select="concat('$OUT[', $out_flood, '] = FALSE')"/></xsl:call-template>
    <xsl:call-template name="line"><xsl:with-param name="text" select="concat('$OUT[', $out_mist, '] = FALSE ; coolant off')"/></xsl:call-template>
  </xsl:template>
  <!-- A spindle on a robot has no tool changer here: the change is the operator's, at a HALT. -->
  <xsl:template match="CHANGE_TOOL">
    <xsl:choose>
      <xsl:when test="@slot = 0">
        <xsl:call-template name="comment"><xsl:with-param name="text" select="'TOOL CHANGE T0 - unload the tool'"/></xsl:call-template>
      </xsl:when>
      <xsl:otherwise>
        <xsl:call-template name="comment"><xsl:with-param name="text" select="concat('TOOL CHANGE T', @slot, ' - fit the tool, then start')"/></xsl:call-template>
        <xsl:call-template name="line"><xsl:with-param name="text" select="'HALT'"/></xsl:call-template>
      </xsl:otherwise>
    </xsl:choose>
  </xsl:template>
  <xsl:template match="USE_TOOL_LENGTH_OFFSET">
    <xsl:call-template name="line">
      <xsl:with-param name="text" select="concat('$TOOL = TOOL_DATA[', $tool_index, ']:{X 0, Y 0, Z ', ext:format(@length, 'length'), ', A 0, B 0, C 0}')"/>
    </xsl:call-template>
  </xsl:template>
  <xsl:template match="DWELL">
    <xsl:call-template name="line"><xsl:with-param name="text" select="concat('WAIT SEC ', ext:format(@seconds, 'dwell'))"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="OPTIONAL_PROGRAM_STOP">
    <xsl:call-template name="comment"><xsl:with-param name="text" select="'OPTIONAL STOP (not available in KRL)'"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="PROGRAM_STOP">
    <xsl:call-template name="line"><xsl:with-param name="text" select="'HALT'"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="PROGRAM_END">
    <xsl:call-template name="comment"><xsl:with-param name="text" select="'PROGRAM END'"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="PROJECT_END">
    <xsl:call-template name="line"><xsl:with-param name="text" select="'END'"/></xsl:call-template>
  </xsl:template>

  <xsl:template match="*">
    <xsl:message terminate="yes"><xsl:value-of select="concat(local-name(), ': not supported by this profile')"/></xsl:message>
  </xsl:template>
</xsl:stylesheet>
