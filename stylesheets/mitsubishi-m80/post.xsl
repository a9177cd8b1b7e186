<?xml version="1.0" encoding="UTF-8"?>
<!-- Mitsubishi M80 (M system): the FANUC family templates (common/fanuc-family.xsl) with
     these choices: "%", O number, N block numbers (ext:block), R arcs when the
     sweep allows it, native drilling cycles G81/G82/G83/G73/G84/G74/G85/G86/G89 with G98/G99 and
     G80, dwell G4 X in seconds with a decimal point, M30, "%". NURBS curves are written natively
     with G06.2 (NURBS interpolation; the profile says capabilities.nurbs = native):
       G06.2 P<degree+1> K<knot 1> X Y Z R<weight>    the first control point = the start point
       K<knot i> X Y Z R<weight>                      every further control point
       K<knot>                                        the remaining degree+1 knots
       G1                                             ends the NURBS mode (modal group 01)
     Knots and weights have at most 4 decimals (weights 0.0001 to 99.9999). -->
<xsl:stylesheet version="1.0" xmlns:xsl="http://www.w3.org/1999/XSL/Transform"
    xmlns:ext="urn:ncpost:ext" exclude-result-prefixes="ext">
  <xsl:import href="../common/fanuc-family.xsl"/>
  <xsl:output method="text" encoding="UTF-8"/>
  <xsl:variable name="o_padding" select="'0000'"/>
  <xsl:variable name="dwell_word" select="'X'"/>

  <!-- NURBS interpolation, G06.2. The feed is modal: the F in force (SET_FEED_RATE, written
       before) applies, so the block carries no F (a chunk cannot see an earlier chunk's feed). -->
  <xsl:template name="nurbs-number">
    <xsl:param name="value"/>
    <xsl:value-of select="format-number($value, '0.0###')"/>
  </xsl:template>
  <xsl:template match="NURBS_FEED">
    <xsl:variable name="knots" select="knot"/>
    <xsl:for-each select="point">
      <xsl:variable name="i" select="position()"/>
      <xsl:variable name="axes"><xsl:call-template name="xyz"/></xsl:variable>
      <xsl:variable name="k"><xsl:call-template name="nurbs-number"><xsl:with-param name="value" select="$knots[$i]/@value"/></xsl:call-template></xsl:variable>
      <xsl:variable name="r"><xsl:call-template name="nurbs-number"><xsl:with-param name="value" select="@w"/></xsl:call-template></xsl:variable>
      <xsl:variable name="start">
        <xsl:if test="$i = 1"><xsl:value-of select="concat('G06.2 P', ../@degree + 1, ' ')"/></xsl:if>
      </xsl:variable>
      <xsl:call-template name="block">
        <xsl:with-param name="text" select="concat($start, 'K', $k, $axes, ' R', $r)"/>
      </xsl:call-template>
    </xsl:for-each>
    <xsl:for-each select="knot[position() &gt; count(../point)]">
      <xsl:variable name="k"><xsl:call-template name="nurbs-number"><xsl:with-param name="value" select="@value"/></xsl:call-template></xsl:variable>
      <xsl:call-template name="block"><xsl:with-param name="text" select="concat('K', $k)"/></xsl:call-template>
    </xsl:for-each>
    <xsl:call-template name="block"><xsl:with-param name="text" select="'G1'"/></xsl:call-template>
    <xsl:value-of select="ext:moved-to(point[last()]/@x, point[last()]/@y, point[last()]/@z)"/>
  </xsl:template>

</xsl:stylesheet>
