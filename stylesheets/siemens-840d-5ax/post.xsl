<?xml version="1.0" encoding="UTF-8"?>
<!-- Sinumerik 840D sl with a swivel head B (about Y) and a rotary table C (about Z), with the
     five-axis transformation (docs/profiles.md, siemens-840d-5ax; docs/kinematics.md): the
     Sinumerik templates (common/siemens-840d.xsl) and
       D1 / TRAORI     tool offset on, then the orientation transformation: X Y Z are the tool
                       tip in the workpiece's coordinates, B C the rotary axes' positions
       TRAFOOF / D0    off again (and before M30)
     The renderer has put B and C on every motion with a tool axis (profile.json kinematics). -->
<xsl:stylesheet version="1.0" xmlns:xsl="http://www.w3.org/1999/XSL/Transform"
    xmlns:ext="urn:ncpost:ext" exclude-result-prefixes="ext">
  <xsl:import href="../common/siemens-840d.xsl"/>
  <xsl:output method="text" encoding="UTF-8"/>

  <xsl:template match="USE_TOOL_LENGTH_OFFSET">
    <xsl:if test="$tcp = 'yes' and @length = 0">
      <xsl:call-template name="block"><xsl:with-param name="text" select="'TRAFOOF'"/></xsl:call-template>
    </xsl:if>
    <xsl:apply-imports/>
    <xsl:if test="$tcp = 'yes' and @length != 0">
      <xsl:call-template name="block"><xsl:with-param name="text" select="'TRAORI'"/></xsl:call-template>
    </xsl:if>
  </xsl:template>

  <xsl:template match="PROGRAM_END">
    <xsl:if test="$tcp = 'yes'">
      <xsl:call-template name="block"><xsl:with-param name="text" select="'TRAFOOF'"/></xsl:call-template>
    </xsl:if>
    <xsl:apply-imports/>
  </xsl:template>
</xsl:stylesheet>
