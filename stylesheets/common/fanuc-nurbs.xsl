<?xml version="1.0" encoding="UTF-8"?>
<!-- The FANUC family (common/fanuc-family.xsl) with NURBS written natively as G06.2 (NURBS
     interpolation, FANUC 30i series and Mitsubishi M700V/M70V/M80; the profile says
     capabilities.nurbs = native), shared by mitsubishi-m80 and fanuc-30i-5ax:
       G06.2 P<degree+1> K<knot 1> X Y Z R<weight>    the first control point = the start point
       K<knot i> X Y Z R<weight>                      every further control point
       K<knot>                                        the remaining degree+1 knots
       G1                                             ends the NURBS mode (modal group 01)
     Knots and weights have at most 4 decimals (weights 0.0001 to 99.9999). -->
<xsl:stylesheet version="1.0" xmlns:xsl="http://www.w3.org/1999/XSL/Transform"
    xmlns:ext="urn:ncpost:ext" exclude-result-prefixes="ext">
  <xsl:import href="fanuc-family.xsl"/>
  <xsl:output method="text" encoding="UTF-8"/>

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
