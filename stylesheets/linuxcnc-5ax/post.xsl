<?xml version="1.0" encoding="UTF-8"?>
<!-- LinuxCNC with a five-axis fork head (C about Z carrying A about X, pivot 150 mm above the
     spindle's gauge point) and trivial kinematics: the post moves the linear axes for the
     pivot and the tool length (profile.json kinematics, tool_centre_point false;
     docs/kinematics.md). The LinuxCNC templates (common/linuxcnc.xsl) write the motions; the
     renderer has put the machine's X Y Z and A C on them. The tool lengths in LinuxCNC's tool
     table must be the lengths of the program's USE_TOOL_LENGTH_OFFSET (G43 H), because the
     head's compensation was computed with them. -->
<xsl:stylesheet version="1.0" xmlns:xsl="http://www.w3.org/1999/XSL/Transform"
    xmlns:ext="urn:ncpost:ext" exclude-result-prefixes="ext">
  <xsl:import href="../common/linuxcnc.xsl"/>
  <xsl:output method="text" encoding="UTF-8"/>
</xsl:stylesheet>
