<?xml version="1.0" encoding="UTF-8"?>
<!-- Heidenhain TNC 640 with a swivel table (A about X carrying a continuous C table) and
     tool-centre-point management (docs/profiles.md, heidenhain-tnc640-5ax; docs/kinematics.md):
     the Klartext templates of common/heidenhain-tnc640.xsl with
       FUNCTION TCPM F TCP AXIS POS PATHCTRL AXIS   after TOOL CALL: X Y Z are the tool tip in
                                                    the workpiece's coordinates, A C the
                                                    rotary axes' positions (AXIS POS), the
                                                    feed is the tip's (F TCP)
       L X+.. Y+.. Z+.. A+.. C+.. R0 F..            motions with the rotary axes
       FUNCTION RESET TCPM                          before L M30
     FUNCTION TCPM is the TNC 640's successor of M128 (which it still accepts). The renderer
     has put A and C on every motion with a tool axis (profile.json kinematics). -->
<xsl:stylesheet version="1.0" xmlns:xsl="http://www.w3.org/1999/XSL/Transform"
    xmlns:ext="urn:ncpost:ext" exclude-result-prefixes="ext">
  <xsl:import href="../common/heidenhain-tnc640.xsl"/>
  <xsl:output method="text" encoding="UTF-8"/>

  <!-- The TNC applies the tool length with TOOL CALL; with a length in force and
       tool_centre_point, TCPM is switched on here (once: it is modal). -->
  <xsl:template match="USE_TOOL_LENGTH_OFFSET">
    <xsl:if test="$tcp = 'yes' and @length != 0 and ext:modal('tcpm', 'on') != ''">
      <xsl:call-template name="block">
        <xsl:with-param name="text" select="'FUNCTION TCPM F TCP AXIS POS PATHCTRL AXIS'"/>
      </xsl:call-template>
    </xsl:if>
  </xsl:template>

  <xsl:template match="PROGRAM_END">
    <xsl:if test="$tcp = 'yes'">
      <xsl:call-template name="block"><xsl:with-param name="text" select="'FUNCTION RESET TCPM'"/></xsl:call-template>
    </xsl:if>
    <xsl:apply-imports/>
  </xsl:template>
</xsl:stylesheet>
