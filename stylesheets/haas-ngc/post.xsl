<?xml version="1.0" encoding="UTF-8"?>
<!-- Haas NGC mill: the FANUC family templates (common/fanuc-family.xsl) with these choices:
     "%", O number (five digits on NGC), no N block numbers (Haas programs
     commonly omit them), R arcs when the sweep allows it, native drilling cycles
     G81/G82/G83/G73/G84/G74/G85/G86/G89 with G98/G99 and G80, dwell G4 P in seconds with a
     decimal point (Haas reads P without a point as milliseconds), M30, "%".
     Checked against /usr/bin/rs274 by tests/interop. -->
<xsl:stylesheet version="1.0" xmlns:xsl="http://www.w3.org/1999/XSL/Transform"
    xmlns:ext="urn:ncpost:ext" exclude-result-prefixes="ext">
  <xsl:import href="../common/fanuc-family.xsl"/>
  <xsl:output method="text" encoding="UTF-8"/>
  <xsl:variable name="o_padding" select="'00000'"/>
  <xsl:variable name="dwell_word" select="'P'"/>
</xsl:stylesheet>
