<?xml version="1.0" encoding="UTF-8"?>
<!-- LinuxCNC, three axes: the LinuxCNC templates (common/linuxcnc.xsl) as they are. -->
<xsl:stylesheet version="1.0" xmlns:xsl="http://www.w3.org/1999/XSL/Transform"
    xmlns:ext="urn:ncpost:ext" exclude-result-prefixes="ext">
  <xsl:import href="../common/linuxcnc.xsl"/>
  <xsl:output method="text" encoding="UTF-8"/>
</xsl:stylesheet>
