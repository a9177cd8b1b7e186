<?xml version="1.0" encoding="UTF-8"?>
<!-- Heidenhain TNC 640, three axes: the Klartext templates of common/heidenhain-tnc640.xsl
     (docs/profiles.md, heidenhain-tnc640). -->
<xsl:stylesheet version="1.0" xmlns:xsl="http://www.w3.org/1999/XSL/Transform">
  <xsl:import href="../common/heidenhain-tnc640.xsl"/>
  <xsl:output method="text" encoding="UTF-8"/>
</xsl:stylesheet>
