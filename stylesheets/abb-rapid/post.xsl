<?xml version="1.0" encoding="UTF-8"?>
<!-- ABB IRC5 robot carrying a milling spindle: one RAPID module, MODULE NAME ... PROC main()
     ... ENDPROC ENDMODULE. Robtargets are written inline in the move instructions: the program
     streams chunk by chunk, and CONST robtarget declarations would have to stand before
     PROC main(), ahead of every motion (docs/profiles.md, abb-rapid). The tool, work object,
     signals and speeds below are the cell's; change them here for another cell. -->
<xsl:stylesheet version="1.0" xmlns:xsl="http://www.w3.org/1999/XSL/Transform"
    xmlns:ext="urn:ncpost:ext" xmlns:math="http://exslt.org/math"
    exclude-result-prefixes="ext math">
  <xsl:output method="text" encoding="UTF-8"/>

  <xsl:param name="program_number" select="'1'"/>
  <xsl:param name="profile_id" select="''"/>
  <xsl:param name="arcs" select="'ijk'"/>
  <xsl:param name="tool" select="'0'"/>

  <!-- The cell. The tool is the spindle nose on the flange (its Z along the tool, pointing out
       of the spindle), spindle_length from the flange; the tool length of
       USE_TOOL_LENGTH_OFFSET is added along that Z. The work object is the part frame taught on
       the robot (its user frame; the object frame stays zero). -->
  <xsl:variable name="tool_name" select="'tSpindle'"/>
  <xsl:variable name="spindle_length" select="150"/>
  <xsl:variable name="tool_mass" select="5"/>
  <xsl:variable name="wobj_name" select="'wobjPart'"/>
  <xsl:variable name="wobj_uframe" select="'[[0,0,0],[1,0,0,0]]'"/>
  <!-- Orientation of the tool in the work object when the tool axis is +Z (tool pointing down):
       a quaternion (180 degrees about X). -->
  <xsl:variable name="down_q" select="'[0,1,0,0]'"/>
  <xsl:variable name="conf" select="'[0,0,0,0]'"/>
  <xsl:variable name="extax" select="'[9E9,9E9,9E9,9E9,9E9,9E9]'"/>
  <!-- Rapid traverse along the path, mm/s; the zone of every move (z1: 1 mm). -->
  <xsl:variable name="rapid_velocity" select="500"/>
  <xsl:variable name="zone" select="'z1'"/>
  <!-- Signals of the spindle and coolant. -->
  <xsl:variable name="do_spindle_cw" select="'doSpindleCW'"/>
  <xsl:variable name="do_spindle_ccw" select="'doSpindleCCW'"/>
  <xsl:variable name="do_flood" select="'doFlood'"/>
  <xsl:variable name="do_mist" select="'doMist'"/>
  <xsl:variable name="ao_speed" select="'aoSpindleSpeed'"/>
  <!-- Helices have no RAPID form (MoveC is a plane circle): they become MoveL points within
       this chord deviation, mm. -->
  <xsl:variable name="chord" select="0.001"/>

  <xsl:template match="/chunk"><xsl:apply-templates select="*"/></xsl:template>
  <xsl:template match="text()"/>

  <!-- One line; inside PROC main() unless indent says otherwise. -->
  <xsl:template name="line">
    <xsl:param name="text"/>
    <xsl:param name="indent" select="'    '"/>
    <xsl:value-of select="ext:line(concat($indent, $text))"/>
    <xsl:text>&#10;</xsl:text>
  </xsl:template>
  <xsl:template name="comment">
    <xsl:param name="text"/>
    <xsl:param name="indent" select="'    '"/>
    <xsl:call-template name="line"><xsl:with-param name="indent" select="$indent"/><xsl:with-param name="text" select="concat('! ', ext:comment($text))"/></xsl:call-template>
  </xsl:template>

  <!-- A RAPID name: letters, digits and _, starting with a letter, at most 32 characters. -->
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
    <xsl:value-of select="substring($lettered, 1, 32)"/>
  </xsl:template>

  <!-- The robtarget's orientation quaternion for the tool axis (i, j, k) (program axes; +Z when
       absent). The tool's Z points into the work, against the axis: the rotation Ry(B)·Rx(C)
       with C = atan2(j', -sqrt(1 - j'^2)) and B = atan2(i', k'), (i', j', k') the axis through
       the set-up, is the quaternion [cos B/2 cos C/2, cos B/2 sin C/2, sin B/2 cos C/2,
       -sin B/2 sin C/2]. -->
  <xsl:template name="orientation">
    <xsl:param name="i" select="@i"/>
    <xsl:param name="j" select="@j"/>
    <xsl:param name="k" select="@k"/>
    <xsl:choose>
      <xsl:when test="string($i) = '' or ($i = 0 and $j = 0 and $k &gt; 0 and ext:setup-k(0, 0, 1) &gt; 0.9999999999)">
        <xsl:value-of select="$down_q"/>
      </xsl:when>
      <xsl:otherwise>
        <xsl:variable name="n" select="math:sqrt($i * $i + $j * $j + $k * $k)"/>
        <xsl:variable name="ii" select="ext:setup-i($i, $j, $k) div $n"/>
        <xsl:variable name="jj" select="ext:setup-j($i, $j, $k) div $n"/>
        <xsl:variable name="kk" select="ext:setup-k($i, $j, $k) div $n"/>
        <xsl:variable name="b" select="math:atan2($ii, $kk) div 2"/>
        <xsl:variable name="c" select="math:atan2($jj, -math:sqrt(1 - $jj * $jj)) div 2"/>
        <xsl:value-of select="concat('[', ext:format(math:cos($b) * math:cos($c), 'angle'), ',', ext:format(math:cos($b) * math:sin($c), 'angle'),
                                     ',', ext:format(math:sin($b) * math:cos($c), 'angle'), ',', ext:format(-math:sin($b) * math:sin($c), 'angle'), ']')"/>
      </xsl:otherwise>
    </xsl:choose>
  </xsl:template>

  <!-- An inline robtarget [[x,y,z],q,conf,extax] of a program point, through the set-up. -->
  <xsl:template name="frame">
    <xsl:param name="x"/>
    <xsl:param name="y"/>
    <xsl:param name="z"/>
    <xsl:param name="abc"/>
    <xsl:value-of select="concat('[[', ext:format(ext:setup-x($x, $y, $z), 'length'),
                                 ',', ext:format(ext:setup-y($x, $y, $z), 'length'),
                                 ',', ext:format(ext:setup-z($x, $y, $z), 'length'),
                                 '],', $abc, ',', $conf, ',', $extax, ']')"/>
  </xsl:template>

  <!-- ", speed, zone, tool\WObj:=wobj;" -->
  <xsl:template name="move-tail">
    <xsl:param name="speed"/>
    <xsl:value-of select="concat(', ', $speed, ', ', $zone, ', ', $tool_name, '\WObj:=', $wobj_name, ';')"/>
  </xsl:template>

  <!-- Structure -->
  <xsl:template match="PROJECT_BEGIN">
    <xsl:variable name="name"><xsl:call-template name="program-name"><xsl:with-param name="name" select="@name"/></xsl:call-template></xsl:variable>
    <xsl:call-template name="line"><xsl:with-param name="indent" select="''"/><xsl:with-param name="text" select="concat('MODULE ', $name)"/></xsl:call-template>
    <xsl:call-template name="comment"><xsl:with-param name="indent" select="'  '"/><xsl:with-param name="text" select="concat('PROJECT #', @id, ' ', @name)"/></xsl:call-template>
    <xsl:call-template name="comment"><xsl:with-param name="indent" select="'  '"/><xsl:with-param name="text" select="concat('ncpost profile ', $profile_id)"/></xsl:call-template>
    <xsl:call-template name="line"><xsl:with-param name="indent" select="'  '"/>
      <xsl:with-param name="text" select="concat('PERS tooldata ', $tool_name, ' := [TRUE,[[0,0,', ext:format($spindle_length, 'length'), '],[1,0,0,0]],[', $tool_mass, ',[0,0,', ext:format($spindle_length div 2, 'length'), '],[1,0,0,0],0,0,0]];')"/></xsl:call-template>
    <xsl:call-template name="line"><xsl:with-param name="indent" select="'  '"/>
      <xsl:with-param name="text" select="concat('TASK PERS wobjdata ', $wobj_name, ' := [FALSE,TRUE,&quot;&quot;,', $wobj_uframe, ',[[0,0,0],[1,0,0,0]]];')"/></xsl:call-template>
    <xsl:call-template name="line"><xsl:with-param name="indent" select="'  '"/>
      <xsl:with-param name="text" select="concat('VAR speeddata vRapid := [', $rapid_velocity, ',500,5000,1000];')"/></xsl:call-template>
    <xsl:call-template name="line"><xsl:with-param name="indent" select="'  '"/>
      <xsl:with-param name="text" select="'VAR speeddata vFeed := [10,500,5000,1000];'"/></xsl:call-template>
    <xsl:call-template name="line"><xsl:with-param name="indent" select="'  '"/><xsl:with-param name="text" select="'PROC main()'"/></xsl:call-template>
    <xsl:call-template name="line"><xsl:with-param name="text" select="'ConfJ \Off;'"/></xsl:call-template>
    <xsl:call-template name="line"><xsl:with-param name="text" select="'ConfL \Off;'"/></xsl:call-template>
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
  <xsl:template match="MESSAGE">
    <xsl:call-template name="line"><xsl:with-param name="text" select="concat('TPWrite &quot;', substring(ext:comment(.), 1, 80), '&quot;;')"/></xsl:call-template>
  </xsl:template>

  <!-- Motion. The first motion of the program is MoveJ (the robot may stand anywhere, and a
       joint move copes with any start configuration); every later traverse is a MoveL at
       vRapid, because a joint move near the part leaves the straight line. -->
  <xsl:template match="STRAIGHT_TRAVERSE | STRAIGHT_FEED">
    <xsl:variable name="abc"><xsl:call-template name="orientation"/></xsl:variable>
    <xsl:variable name="frame">
      <xsl:call-template name="frame">
        <xsl:with-param name="x" select="@x"/><xsl:with-param name="y" select="@y"/><xsl:with-param name="z" select="@z"/>
        <xsl:with-param name="abc" select="$abc"/>
      </xsl:call-template>
    </xsl:variable>
    <xsl:variable name="tail">
      <xsl:call-template name="move-tail">
        <xsl:with-param name="speed"><xsl:choose><xsl:when test="self::STRAIGHT_TRAVERSE">vRapid</xsl:when><xsl:otherwise>vFeed</xsl:otherwise></xsl:choose></xsl:with-param>
      </xsl:call-template>
    </xsl:variable>
    <xsl:choose>
      <xsl:when test="ext:modal('first-motion', 'done') != ''">
        <xsl:if test="self::STRAIGHT_FEED">
          <xsl:message terminate="yes">the program's first motion is a feed: a robot must reach its start with a traverse (MoveJ)</xsl:message>
        </xsl:if>
        <xsl:call-template name="line"><xsl:with-param name="text" select="concat('MoveJ ', $frame, $tail)"/></xsl:call-template>
      </xsl:when>
      <xsl:otherwise>
        <xsl:call-template name="line"><xsl:with-param name="text" select="concat('MoveL ', $frame, $tail)"/></xsl:call-template>
      </xsl:otherwise>
    </xsl:choose>
    <xsl:value-of select="ext:moved-to(@x, @y, @z)"/>
  </xsl:template>

  <!-- Arcs in the XY, YZ or XZ plane, in the plane's own coordinates (f, s) with the axis
       coordinate a (rs274's first, second, axis). A plane arc becomes MoveC pieces of at most
       180 degrees, each through the mid-point of its piece (a full circle is two pieces); a
       helix becomes MoveL points. -->
  <xsl:template match="ARC_FEED">
    <xsl:if test="not(@plane)">
      <xsl:message terminate="yes">ARC_FEED in a tilted plane: not supported by this profile</xsl:message>
    </xsl:if>
    <xsl:variable name="plane" select="@plane"/>
    <xsl:variable name="abc"><xsl:call-template name="orientation"/></xsl:variable>
    <xsl:variable name="tail"><xsl:call-template name="move-tail"><xsl:with-param name="speed" select="'vFeed'"/></xsl:call-template></xsl:variable>
    <xsl:variable name="px" select="ext:position('x')"/>
    <xsl:variable name="py" select="ext:position('y')"/>
    <xsl:variable name="pz" select="ext:position('z')"/>
    <xsl:variable name="sf" select="($plane = 'xy') * $px + ($plane = 'yz') * $py + ($plane = 'xz') * $pz"/>
    <xsl:variable name="ss" select="($plane = 'xy') * $py + ($plane = 'yz') * $pz + ($plane = 'xz') * $px"/>
    <xsl:variable name="sa" select="($plane = 'xy') * $pz + ($plane = 'yz') * $px + ($plane = 'xz') * $py"/>
    <xsl:variable name="cf" select="@first_axis"/>
    <xsl:variable name="cs" select="@second_axis"/>
    <xsl:variable name="rotation" select="@rotation"/>
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
          <xsl:call-template name="line"><xsl:with-param name="text" select="concat('MoveL ', $frame, $tail)"/></xsl:call-template>
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
          <xsl:call-template name="line"><xsl:with-param name="text" select="concat('MoveC ', $aux, ', ', $end, $tail)"/></xsl:call-template>
          <xsl:value-of select="ext:moved-to($x, $y, $z)"/>
        </xsl:for-each>
      </xsl:otherwise>
    </xsl:choose>
    <xsl:value-of select="ext:moved-to(@x, @y, @z)"/>
  </xsl:template>

  <!-- Technology -->
  <xsl:template match="SET_FEED_RATE">
    <xsl:call-template name="line"><xsl:with-param name="text" select="concat('vFeed.v_tcp := ', ext:format(@rate, 'feed'), '; ! ', ext:format(@rate * 1, 'length'), ' mm/min')"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="SET_SPINDLE_SPEED">
    <xsl:call-template name="line"><xsl:with-param name="text" select="concat('SetAO ', $ao_speed, ', ', ext:format(@rpm, 'speed'), ';')"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="START_SPINDLE_CLOCKWISE">
    <xsl:call-template name="line"><xsl:with-param name="text" select="concat('SetDO ', $do_spindle_ccw, ', 0;')"/></xsl:call-template>
    <xsl:call-template name="line"><xsl:with-param name="text" select="concat('SetDO ', $do_spindle_cw, ', 1;')"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="START_SPINDLE_COUNTERCLOCKWISE">
    <xsl:call-template name="line"><xsl:with-param name="text" select="concat('SetDO ', $do_spindle_cw, ', 0;')"/></xsl:call-template>
    <xsl:call-template name="line"><xsl:with-param name="text" select="concat('SetDO ', $do_spindle_ccw, ', 1;')"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="STOP_SPINDLE_TURNING">
    <xsl:call-template name="line"><xsl:with-param name="text" select="concat('SetDO ', $do_spindle_cw, ', 0;')"/></xsl:call-template>
    <xsl:call-template name="line"><xsl:with-param name="text" select="concat('SetDO ', $do_spindle_ccw, ', 0;')"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="FLOOD_ON">
    <xsl:call-template name="line"><xsl:with-param name="text" select="concat('SetDO ', $do_flood, ', 1;')"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="MIST_ON">
    <xsl:call-template name="line"><xsl:with-param name="text" select="concat('SetDO ', $do_mist, ', 1;')"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="FLOOD_OFF | MIST_OFF">
    <xsl:call-template name="line"><xsl:with-param name="text" select="concat('SetDO ', $do_flood, ', 0;')"/></xsl:call-template>
    <xsl:call-template name="line"><xsl:with-param name="text" select="concat('SetDO ', $do_mist, ', 0;')"/></xsl:call-template>
  </xsl:template>
  <!-- A spindle on a robot has no tool changer here: the change is the operator's, at a Stop. -->
  <xsl:template match="CHANGE_TOOL">
    <xsl:choose>
      <xsl:when test="@slot = 0">
        <xsl:call-template name="comment"><xsl:with-param name="text" select="'TOOL CHANGE T0 - unload the tool'"/></xsl:call-template>
      </xsl:when>
      <xsl:otherwise>
        <xsl:call-template name="comment"><xsl:with-param name="text" select="concat('TOOL CHANGE T', @slot, ' - fit the tool, then start')"/></xsl:call-template>
        <xsl:call-template name="line"><xsl:with-param name="text" select="'Stop;'"/></xsl:call-template>
      </xsl:otherwise>
    </xsl:choose>
  </xsl:template>
  <xsl:template match="USE_TOOL_LENGTH_OFFSET">
    <xsl:call-template name="line">
      <xsl:with-param name="text" select="concat($tool_name, '.tframe.trans := [0,0,', ext:format($spindle_length + @length, 'length'), '];')"/>
    </xsl:call-template>
  </xsl:template>
  <xsl:template match="DWELL">
    <xsl:call-template name="line"><xsl:with-param name="text" select="concat('WaitTime \InPos, ', ext:format(@seconds, 'dwell'), ';')"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="OPTIONAL_PROGRAM_STOP">
    <xsl:call-template name="comment"><xsl:with-param name="text" select="'OPTIONAL STOP (no optional stop in RAPID)'"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="PROGRAM_STOP">
    <xsl:call-template name="line"><xsl:with-param name="text" select="'Stop;'"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="PROGRAM_END">
    <xsl:call-template name="comment"><xsl:with-param name="text" select="'PROGRAM END'"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="PROJECT_END">
    <xsl:call-template name="line"><xsl:with-param name="indent" select="'  '"/><xsl:with-param name="text" select="'ENDPROC'"/></xsl:call-template>
    <xsl:call-template name="line"><xsl:with-param name="indent" select="''"/><xsl:with-param name="text" select="'ENDMODULE'"/></xsl:call-template>
  </xsl:template>

  <xsl:template match="*">
    <xsl:message terminate="yes"><xsl:value-of select="concat(local-name(), ': not supported by this profile')"/></xsl:message>
  </xsl:template>
</xsl:stylesheet>
