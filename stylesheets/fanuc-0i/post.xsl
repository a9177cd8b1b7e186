<?xml version="1.0" encoding="UTF-8"?>
<!-- FANUC 0i-MF: O number, N block numbers (ext:block), R arcs when the sweep allows it
     (the profile's capabilities.arcs), native drilling cycles G81/G82/G83/G73/G84/G74/G85/
     G86/G89 with G98 (return to the initial level) or G99 (R level), M30 at the end. -->
<xsl:stylesheet version="1.0" xmlns:xsl="http://www.w3.org/1999/XSL/Transform"
    xmlns:ext="urn:ncpost:ext" exclude-result-prefixes="ext">
  <xsl:import href="../common/fanuc-family.xsl"/>
  <xsl:output method="text" encoding="UTF-8"/>
  <xsl:variable name="o_padding" select="'0000'"/>
  <xsl:variable name="dwell_word" select="'P'"/>
</xsl:stylesheet>
