<?xml version="1.0" encoding="UTF-8"?>
<!-- LinuxCNC (rs274ngc), shared by linuxcnc and linuxcnc-5ax. Incremental arc centres (G91.1,
     the default), comments in parentheses, M2 at the end. Checked against /usr/bin/rs274 by
     tests/interop. -->
<xsl:stylesheet version="1.0" xmlns:xsl="http://www.w3.org/1999/XSL/Transform"
    xmlns:ext="urn:ncpost:ext" exclude-result-prefixes="ext">
  <xsl:import href="ncpost-common.xsl"/>
  <xsl:output method="text" encoding="UTF-8"/>

  <xsl:template match="PROJECT_BEGIN">
    <xsl:text>%&#10;</xsl:text>
    <xsl:call-template name="comment-block">
      <xsl:with-param name="text" select="concat('PROJECT #', @id, ' ', @name)"/>
    </xsl:call-template>
    <xsl:variable name="units">
      <xsl:choose><xsl:when test="ext:units() = 'inch'">G20</xsl:when><xsl:otherwise>G21</xsl:otherwise></xsl:choose>
    </xsl:variable>
    <xsl:value-of select="substring(ext:modal('plane', 'G17'), 1, 0)"/>
    <xsl:call-template name="block">
      <xsl:with-param name="text" select="concat($units, ' G17 G90 G94 G40 G49 G80 G91.1')"/>
    </xsl:call-template>
  </xsl:template>

  <!-- LinuxCNC shows (MSG, ...) to the operator; rs274 prints it as MESSAGE. -->
  <xsl:template match="MESSAGE">
    <xsl:call-template name="block"><xsl:with-param name="text" select="concat('(MSG, ', ext:comment(string(.)), ')')"/></xsl:call-template>
  </xsl:template>

  <xsl:template match="PROGRAM_END">
    <xsl:call-template name="block"><xsl:with-param name="text" select="'M2'"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="PROJECT_END"><xsl:text>%&#10;</xsl:text></xsl:template>
</xsl:stylesheet>
