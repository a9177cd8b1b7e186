<?xml version="1.0" encoding="UTF-8"?>
<!-- Okuma OSP-P300M (docs/profiles.md, okuma-osp): the common templates with Okuma's words:
       O0001 (NAME)                 program name (a main program starts with O)
       N1, N2, ...                  block numbers 1 by 1
       G15 H1                       work coordinate system 1 (Okuma's G15 H, not G54)
       G17 G21 G90 G94 G40 G80      plane, metric input, absolute, feed per minute
       T901 M6, G56 H901 / G53      tool change, tool length offset on / cancelled
       G2/G3 X Y Z I J K            incremental centre; arcs of more than one turn are cut
                                    into pieces of at most 180 degrees (no turn count)
       G4 F<s>                      dwell in seconds
       M30                          end of program
     Cycles are expanded and NURBS linearised by the renderer (the profile says so): see
     docs/profiles.md for why. -->
<xsl:stylesheet version="1.0" xmlns:xsl="http://www.w3.org/1999/XSL/Transform"
    xmlns:ext="urn:ncpost:ext" exclude-result-prefixes="ext">
  <xsl:import href="../common/ncpost-common.xsl"/>
  <xsl:output method="text" encoding="UTF-8"/>

  <xsl:template match="PROJECT_BEGIN">
    <xsl:value-of select="concat('O', substring('0000', string-length($program_number) + 1), $program_number,
                                 ' (', ext:comment(@name), ')')"/>
    <xsl:text>&#10;</xsl:text>
    <xsl:call-template name="block"><xsl:with-param name="text" select="'G15 H1'"/></xsl:call-template>
    <xsl:variable name="units">
      <xsl:choose><xsl:when test="ext:units() = 'inch'">G20</xsl:when><xsl:otherwise>G21</xsl:otherwise></xsl:choose>
    </xsl:variable>
    <xsl:value-of select="substring(ext:modal('plane', 'G17'), 1, 0)"/>
    <xsl:call-template name="block">
      <xsl:with-param name="text" select="concat('G17 ', $units, ' G90 G94 G40 G80')"/>
    </xsl:call-template>
  </xsl:template>

  <xsl:template match="USE_TOOL_LENGTH_OFFSET">
    <xsl:variable name="tool"><xsl:call-template name="current-tool"/></xsl:variable>
    <xsl:choose>
      <xsl:when test="@length = 0 or $tool = '0'">
        <xsl:call-template name="block"><xsl:with-param name="text" select="'G53'"/></xsl:call-template>
      </xsl:when>
      <xsl:otherwise>
        <xsl:call-template name="block"><xsl:with-param name="text" select="concat('G56 H', $tool)"/></xsl:call-template>
      </xsl:otherwise>
    </xsl:choose>
  </xsl:template>

  <xsl:template match="DWELL">
    <xsl:call-template name="block"><xsl:with-param name="text" select="concat('G4 F', ext:format(@seconds, 'dwell'))"/></xsl:call-template>
  </xsl:template>

  <!-- One G2/G3 block; $x $y $z the end of this piece. -->
  <xsl:template name="arc-piece">
    <xsl:param name="g"/>
    <xsl:param name="x"/>
    <xsl:param name="y"/>
    <xsl:param name="z"/>
    <xsl:param name="cx"/>
    <xsl:param name="cy"/>
    <xsl:param name="cz"/>
    <xsl:param name="plane"/>
    <xsl:variable name="axes">
      <xsl:call-template name="xyz">
        <xsl:with-param name="x" select="$x"/><xsl:with-param name="y" select="$y"/><xsl:with-param name="z" select="$z"/>
      </xsl:call-template>
    </xsl:variable>
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
    <xsl:call-template name="block"><xsl:with-param name="text" select="concat($g, $axes, $centre)"/></xsl:call-template>
    <xsl:value-of select="ext:moved-to($x, $y, $z)"/>
  </xsl:template>

  <xsl:template match="ARC_FEED">
    <xsl:if test="not(@plane)">
      <xsl:message terminate="yes">ARC_FEED in a tilted plane has no G2/G3 form on this controller</xsl:message>
    </xsl:if>
    <xsl:variable name="pw"><xsl:call-template name="plane-word"/></xsl:variable>
    <xsl:variable name="planeword" select="ext:modal('plane', $pw)"/>
    <xsl:if test="$planeword != ''">
      <xsl:call-template name="block"><xsl:with-param name="text" select="$planeword"/></xsl:call-template>
    </xsl:if>
    <xsl:variable name="g">
      <xsl:choose><xsl:when test="@rotation &gt; 0">G3</xsl:when><xsl:otherwise>G2</xsl:otherwise></xsl:choose>
    </xsl:variable>
    <xsl:variable name="plane" select="@plane"/>
    <xsl:variable name="cx" select="@cx"/>
    <xsl:variable name="cy" select="@cy"/>
    <xsl:variable name="cz" select="@cz"/>
    <xsl:choose>
      <xsl:when test="@rotation &gt; 1 or @rotation &lt; -1">
        <xsl:if test="@plane != 'xy'">
          <xsl:message terminate="yes">ARC_FEED of more than one turn outside the XY plane: not supported by this profile</xsl:message>
        </xsl:if>
        <xsl:for-each select="ext:arc-split(ext:position('x'), ext:position('y'), ext:position('z'),
                                            @x, @y, @z, @cx, @cy, @rotation, 180)">
          <xsl:call-template name="arc-piece">
            <xsl:with-param name="g" select="$g"/>
            <xsl:with-param name="x" select="@x"/><xsl:with-param name="y" select="@y"/><xsl:with-param name="z" select="@z"/>
            <xsl:with-param name="cx" select="$cx"/><xsl:with-param name="cy" select="$cy"/><xsl:with-param name="cz" select="$cz"/>
            <xsl:with-param name="plane" select="$plane"/>
          </xsl:call-template>
        </xsl:for-each>
      </xsl:when>
      <xsl:otherwise>
        <xsl:call-template name="arc-piece">
          <xsl:with-param name="g" select="$g"/>
          <xsl:with-param name="x" select="@x"/><xsl:with-param name="y" select="@y"/><xsl:with-param name="z" select="@z"/>
          <xsl:with-param name="cx" select="$cx"/><xsl:with-param name="cy" select="$cy"/><xsl:with-param name="cz" select="$cz"/>
          <xsl:with-param name="plane" select="$plane"/>
        </xsl:call-template>
      </xsl:otherwise>
    </xsl:choose>
  </xsl:template>

  <xsl:template match="PROGRAM_END">
    <xsl:call-template name="block"><xsl:with-param name="text" select="'M30'"/></xsl:call-template>
  </xsl:template>
</xsl:stylesheet>
