<?xml version="1.0" encoding="UTF-8"?>
<!-- Mitsubishi M80 (M system): the FANUC family templates with native NURBS
     (common/fanuc-nurbs.xsl: G06.2) and these choices: "%", O number, N block numbers
     (ext:block), R arcs when the sweep allows it, native drilling cycles
     G81/G82/G83/G73/G84/G74/G85/G86/G89 with G98/G99 and G80, dwell G4 X in seconds with a
     decimal point, M30, "%". -->
<xsl:stylesheet version="1.0" xmlns:xsl="http://www.w3.org/1999/XSL/Transform"
    xmlns:ext="urn:ncpost:ext" exclude-result-prefixes="ext">
  <xsl:import href="../common/fanuc-nurbs.xsl"/>
  <xsl:output method="text" encoding="UTF-8"/>
  <xsl:variable name="o_padding" select="'0000'"/>
  <xsl:variable name="dwell_word" select="'X'"/>
</xsl:stylesheet>
