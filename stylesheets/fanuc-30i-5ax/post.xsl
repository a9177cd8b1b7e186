<?xml version="1.0" encoding="UTF-8"?>
<!-- FANUC 30i-B with a trunnion table (A about X carrying C about Z), tool centre point
     control and NURBS interpolation (docs/profiles.md, fanuc-30i-5ax; docs/kinematics.md):
     the FANUC family templates with G06.2 (common/fanuc-nurbs.xsl) and
       G05.1 Q1 ... G05.1 Q0      AI contour control, which NURBS interpolation runs in
       G43.4 H<tool>              tool centre point control, type 1: X Y Z are the tool tip in
                                  the program's (the table's) coordinates, A C the rotary axes
       G49                        cancels it before M30
     The renderer has put A and C on every motion with a tool axis (profile.json kinematics). -->
<xsl:stylesheet version="1.0" xmlns:xsl="http://www.w3.org/1999/XSL/Transform"
    xmlns:ext="urn:ncpost:ext" exclude-result-prefixes="ext">
  <xsl:import href="../common/fanuc-nurbs.xsl"/>
  <xsl:output method="text" encoding="UTF-8"/>
  <xsl:variable name="o_padding" select="'0000'"/>
  <xsl:variable name="dwell_word" select="'P'"/>

  <xsl:template match="PROJECT_BEGIN">
    <xsl:apply-imports/>
    <xsl:value-of select="ext:block-line('G05.1 Q1')"/><xsl:text>&#10;</xsl:text>
  </xsl:template>

  <!-- G43.4 H (tool centre point control with the tool's length offset) where a three-axis
       program has G43 H; without tool_centre_point the family's G43 H. -->
  <xsl:template match="USE_TOOL_LENGTH_OFFSET">
    <xsl:variable name="tool"><xsl:call-template name="current-tool"/></xsl:variable>
    <xsl:choose>
      <xsl:when test="$tcp = 'yes' and @length != 0 and $tool != '0'">
        <xsl:value-of select="ext:block-line(concat('G43.4 H', $tool))"/><xsl:text>&#10;</xsl:text>
      </xsl:when>
      <xsl:otherwise><xsl:apply-imports/></xsl:otherwise>
    </xsl:choose>
  </xsl:template>

  <xsl:template match="PROGRAM_END">
    <xsl:value-of select="ext:block-line('G49')"/><xsl:text>&#10;</xsl:text>
    <xsl:value-of select="ext:block-line('G05.1 Q0')"/><xsl:text>&#10;</xsl:text>
    <xsl:apply-imports/>
  </xsl:template>
</xsl:stylesheet>
