<?xml version="1.0" encoding="UTF-8"?>
<!-- Cell 3's mill: the common rs274-style output with LinuxCNC's program end. A site profile
     lives in its own folder beside the built-ins and imports ../common/ like them. -->
<xsl:stylesheet version="1.0" xmlns:xsl="http://www.w3.org/1999/XSL/Transform">
  <xsl:import href="../common/ncpost-common.xsl"/>
  <xsl:output method="text" encoding="UTF-8"/>
  <xsl:template match="PROGRAM_END">
    <xsl:call-template name="block"><xsl:with-param name="text" select="'M2'"/></xsl:call-template>
  </xsl:template>
</xsl:stylesheet>
