<?xml version="1.0" encoding="UTF-8"?>
<!-- Huazhong HNC-21 (世纪星) three-axis mill, the controller of the XSLT post-processor paper
     (Xiao and Huan, 2012): "%" and the program number on the first line, N block numbers from
     ext:block() (N1, N2, ... like the paper's GetIndexNumber), G-code with four decimals like
     the paper's CoordinatesFormat, every point through the profile's set-up transform (the
     paper's set-up: 90° about Z, Z shifted by -14.7 mm). Arcs with incremental I J (K) centres;
     an arc of more than one turn is cut into pieces of at most 180° (no P word). Cycles are
     expanded and NURBS linearised by the renderer. Dwell G04 P in seconds. M30 at the end. -->
<xsl:stylesheet version="1.0" xmlns:xsl="http://www.w3.org/1999/XSL/Transform"
    xmlns:ext="urn:ncpost:ext" exclude-result-prefixes="ext">
  <xsl:import href="../common/ncpost-common.xsl"/>
  <xsl:output method="text" encoding="UTF-8"/>

  <xsl:template match="PROJECT_BEGIN">
    <xsl:value-of select="concat('%', $program_number)"/>
    <xsl:text>&#10;</xsl:text>
    <xsl:call-template name="comment-block">
      <xsl:with-param name="text" select="concat('PROJECT #', @id, ' ', @name)"/>
    </xsl:call-template>
    <xsl:variable name="units">
      <xsl:choose><xsl:when test="ext:units() = 'inch'">G20</xsl:when><xsl:otherwise>G21</xsl:otherwise></xsl:choose>
    </xsl:variable>
    <xsl:value-of select="substring(ext:modal('plane', 'G17'), 1, 0)"/>
    <xsl:call-template name="block">
      <xsl:with-param name="text" select="concat($units, ' G17 G90 G94 G40 G49 G80')"/>
    </xsl:call-template>
  </xsl:template>

  <!-- Two-digit G words, as HNC-21 programs (and the paper's G01) are usually written. -->
  <xsl:template match="STRAIGHT_TRAVERSE | STRAIGHT_FEED">
    <xsl:variable name="g" select="substring('G01G00', 1 + 3 * boolean(self::STRAIGHT_TRAVERSE), 3)"/>
    <xsl:choose>
      <xsl:when test="@a or @b or @c">
        <xsl:variable name="axes"><xsl:call-template name="xyz"/></xsl:variable>
        <xsl:call-template name="block"><xsl:with-param name="text" select="concat($g, $axes)"/></xsl:call-template>
        <xsl:value-of select="ext:moved-to(@x, @y, @z)"/>
      </xsl:when>
      <!-- "block" and "xyz", inline (see ncpost-common.xsl). -->
      <xsl:otherwise>
        <xsl:variable name="x" select="number(@x)"/>
        <xsl:variable name="y" select="number(@y)"/>
        <xsl:variable name="z" select="number(@z)"/>
        <xsl:variable name="axes" select="concat(' X', ext:format(ext:setup-x($x, $y, $z), 'length'),
                       ' Y', ext:format(ext:setup-y($x, $y, $z), 'length'),
                       ' Z', ext:format(ext:setup-z($x, $y, $z), 'length'))"/>
        <xsl:value-of select="concat(ext:block-line(concat($g, $axes)), '&#10;', ext:moved-to($x, $y, $z))"/>
      </xsl:otherwise>
    </xsl:choose>
  </xsl:template>

  <!-- One G02/G03 block from the current position to (@x, @y, @z) of the context node. -->
  <xsl:template name="arc-piece">
    <xsl:param name="g"/>
    <xsl:param name="plane"/>
    <xsl:param name="cx"/>
    <xsl:param name="cy"/>
    <xsl:param name="cz"/>
    <xsl:variable name="sx" select="ext:position('x')"/>
    <xsl:variable name="sy" select="ext:position('y')"/>
    <xsl:variable name="sz" select="ext:position('z')"/>
    <xsl:variable name="i" select="ext:format(ext:arc-i(ext:setup-x($sx, $sy, $sz), ext:setup-x($cx, $cy, $cz)), 'length')"/>
    <xsl:variable name="j" select="ext:format(ext:arc-j(ext:setup-y($sx, $sy, $sz), ext:setup-y($cx, $cy, $cz)), 'length')"/>
    <xsl:variable name="k" select="ext:format(ext:arc-k(ext:setup-z($sx, $sy, $sz), ext:setup-z($cx, $cy, $cz)), 'length')"/>
    <xsl:variable name="centre">
      <xsl:choose>
        <xsl:when test="$plane = 'yz'"><xsl:value-of select="concat(' J', $j, ' K', $k)"/></xsl:when>
        <xsl:when test="$plane = 'xz'"><xsl:value-of select="concat(' I', $i, ' K', $k)"/></xsl:when>
        <xsl:otherwise><xsl:value-of select="concat(' I', $i, ' J', $j)"/></xsl:otherwise>
      </xsl:choose>
    </xsl:variable>
    <xsl:variable name="axes"><xsl:call-template name="xyz"/></xsl:variable>
    <xsl:call-template name="block"><xsl:with-param name="text" select="concat($g, $axes, $centre)"/></xsl:call-template>
    <xsl:value-of select="ext:moved-to(@x, @y, @z)"/>
  </xsl:template>

  <!-- The plane an arc lies in on the machine: the profile's set-up turns the canonical plane's
       normal (+Z for xy, +Y for xz, +X for yz); 'xy', 'xz' or 'yz' when it lands on an axis,
       followed by '+' or '-' for the direction it lands in (a '-' flips G02/G03), '' when the
       set-up tilts the arc out of every G17/G18/G19 plane. The paper's set-up (90 degrees about
       Z) takes a canonical XZ arc into the machine's YZ plane and a YZ arc into its XZ plane. -->
  <xsl:template name="machine-plane">
    <xsl:variable name="nx" select="number(@plane = 'yz')"/>
    <xsl:variable name="ny" select="number(@plane = 'xz')"/>
    <xsl:variable name="nz" select="number(@plane = 'xy')"/>
    <xsl:variable name="i" select="ext:setup-i($nx, $ny, $nz)"/>
    <xsl:variable name="j" select="ext:setup-j($nx, $ny, $nz)"/>
    <xsl:variable name="k" select="ext:setup-k($nx, $ny, $nz)"/>
    <xsl:choose>
      <xsl:when test="$k &gt; 0.999999">xy+</xsl:when>
      <xsl:when test="$k &lt; -0.999999">xy-</xsl:when>
      <xsl:when test="$j &gt; 0.999999">xz+</xsl:when>
      <xsl:when test="$j &lt; -0.999999">xz-</xsl:when>
      <xsl:when test="$i &gt; 0.999999">yz+</xsl:when>
      <xsl:when test="$i &lt; -0.999999">yz-</xsl:when>
    </xsl:choose>
  </xsl:template>

  <xsl:template match="ARC_FEED">
    <xsl:if test="not(@plane)">
      <xsl:message terminate="yes">ARC_FEED in a tilted plane has no G02/G03 form on this controller</xsl:message>
    </xsl:if>
    <xsl:variable name="machine"><xsl:call-template name="machine-plane"/></xsl:variable>
    <xsl:if test="$machine = ''">
      <xsl:message terminate="yes">ARC_FEED that the profile's set-up turns out of the G17/G18/G19 planes: not supported by this profile</xsl:message>
    </xsl:if>
    <xsl:variable name="plane" select="substring($machine, 1, 2)"/>
    <xsl:variable name="pw">
      <xsl:choose>
        <xsl:when test="$plane = 'yz'">G19</xsl:when>
        <xsl:when test="$plane = 'xz'">G18</xsl:when>
        <xsl:otherwise>G17</xsl:otherwise>
      </xsl:choose>
    </xsl:variable>
    <xsl:variable name="planeword" select="ext:modal('plane', $pw)"/>
    <xsl:if test="$planeword != ''">
      <xsl:call-template name="block"><xsl:with-param name="text" select="$planeword"/></xsl:call-template>
    </xsl:if>
    <!-- Counter-clockwise about the machine axis the normal lands on; about its negative, the
         other way round. -->
    <xsl:variable name="g">
      <xsl:choose><xsl:when test="(@rotation &gt; 0) = (substring($machine, 3, 1) = '+')">G03</xsl:when><xsl:otherwise>G02</xsl:otherwise></xsl:choose>
    </xsl:variable>
    <xsl:variable name="cx" select="@cx"/>
    <xsl:variable name="cy" select="@cy"/>
    <xsl:variable name="cz" select="@cz"/>
    <xsl:choose>
      <xsl:when test="@rotation &gt; 1 or @rotation &lt; -1">
        <xsl:if test="@plane != 'xy' or $plane != 'xy'">
          <xsl:message terminate="yes">ARC_FEED of more than one turn outside the XY plane: not supported by this profile</xsl:message>
        </xsl:if>
        <!-- @turns is signed about the arc's normal; ext:arc-split wants the XY sense, as @rotation. -->
        <xsl:for-each select="ext:arc-split(ext:position('x'), ext:position('y'), ext:position('z'),
                                            @x, @y, @z, @cx, @cy, @rotation, 180)">
          <xsl:call-template name="arc-piece">
            <xsl:with-param name="g" select="$g"/>
            <xsl:with-param name="plane" select="$plane"/>
            <xsl:with-param name="cx" select="$cx"/>
            <xsl:with-param name="cy" select="$cy"/>
            <xsl:with-param name="cz" select="$cz"/>
          </xsl:call-template>
        </xsl:for-each>
      </xsl:when>
      <xsl:otherwise>
        <xsl:call-template name="arc-piece">
          <xsl:with-param name="g" select="$g"/>
          <xsl:with-param name="plane" select="$plane"/>
          <xsl:with-param name="cx" select="$cx"/>
          <xsl:with-param name="cy" select="$cy"/>
          <xsl:with-param name="cz" select="$cz"/>
        </xsl:call-template>
      </xsl:otherwise>
    </xsl:choose>
  </xsl:template>

  <xsl:template match="DWELL">
    <xsl:call-template name="block"><xsl:with-param name="text" select="concat('G04 P', ext:format(@seconds, 'dwell'))"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="START_SPINDLE_CLOCKWISE">
    <xsl:call-template name="block"><xsl:with-param name="text" select="'M03'"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="START_SPINDLE_COUNTERCLOCKWISE">
    <xsl:call-template name="block"><xsl:with-param name="text" select="'M04'"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="STOP_SPINDLE_TURNING">
    <xsl:call-template name="block"><xsl:with-param name="text" select="'M05'"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="CHANGE_TOOL">
    <xsl:call-template name="block"><xsl:with-param name="text" select="concat('T', @slot, ' M06')"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="FLOOD_ON">
    <xsl:call-template name="block"><xsl:with-param name="text" select="'M08'"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="MIST_ON">
    <xsl:call-template name="block"><xsl:with-param name="text" select="'M07'"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="FLOOD_OFF | MIST_OFF">
    <xsl:call-template name="block"><xsl:with-param name="text" select="'M09'"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="OPTIONAL_PROGRAM_STOP">
    <xsl:call-template name="block"><xsl:with-param name="text" select="'M01'"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="PROGRAM_STOP">
    <xsl:call-template name="block"><xsl:with-param name="text" select="'M00'"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="PROGRAM_END">
    <xsl:call-template name="block"><xsl:with-param name="text" select="'M30'"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="PROJECT_END"/>
</xsl:stylesheet>
