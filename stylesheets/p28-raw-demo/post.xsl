<?xml version="1.0" encoding="UTF-8"?>
<!-- Raw-mode demo (profile "mode": "raw"): the post-processor of the XSLT paper (Xiao and Huan
     2012), which reads the whole late-bound P28 document in one transformation. It walks the
     instance graph itself: project -> main_workplan -> its_elements (workingsteps) ->
     its_operation -> its_toolpath (toolpath_list) -> cutter_location_trajectory -> basiccurve,
     following entity_instance_ref/@refid by id with xsl:key. Scope (docs/profiles.md,
     p28-raw-demo): explicit toolpaths whose basic curve is a polyline become G0 (rapid_movement)
     or G1 blocks; other curves are named in a comment and skipped; feeds (m/s) and spindle
     speeds (rev/s) come from the technology in ISO 14649 units. -->
<xsl:stylesheet version="1.0" xmlns:xsl="http://www.w3.org/1999/XSL/Transform"
    xmlns:p28="urn:ncpost:iso10303-28:late-binding" xmlns:ext="urn:ncpost:ext"
    xmlns:math="http://exslt.org/math" exclude-result-prefixes="p28 ext math">
  <xsl:output method="text" encoding="UTF-8"/>
  <xsl:param name="program_number" select="'1'"/>
  <xsl:param name="profile_id" select="''"/>

  <xsl:key name="id" match="p28:entity_instance" use="@id"/>

  <xsl:variable name="project" select="//p28:entity_instance[@express_entity_name = 'project']"/>
  <xsl:variable name="plan" select="key('id', $project/*[@express_attribute_name = 'main_workplan']/p28:entity_instance_ref/@refid)"/>
  <xsl:variable name="setup" select="key('id', $plan/*[@express_attribute_name = 'its_setup']/p28:entity_instance_ref/@refid)"/>
  <xsl:variable name="workpiece_setups" select="key('id', $setup/*[@express_attribute_name = 'its_workpiece_setup']/p28:list_literal/p28:entity_instance_ref/@refid)"/>

  <!-- One number of a placement that turns about +Z only: 'a', 'b' (its x axis, the
       normalised ref_direction; (1, 0) when absent), 'x', 'y', 'z' (its location); the identity
       without a placement. Placements that tilt the axis are outside the demo's scope. -->
  <xsl:template name="placement">
    <xsl:param name="placement"/>
    <xsl:param name="what"/>
    <xsl:variable name="axis" select="key('id', $placement/*[@express_attribute_name = 'axis']/p28:entity_instance_ref/@refid)/*[@express_attribute_name = 'direction_ratios']/p28:list_literal/*"/>
    <xsl:variable name="ref" select="key('id', $placement/*[@express_attribute_name = 'ref_direction']/p28:entity_instance_ref/@refid)/*[@express_attribute_name = 'direction_ratios']/p28:list_literal/*"/>
    <xsl:variable name="loc" select="key('id', $placement/*[@express_attribute_name = 'location']/p28:entity_instance_ref/@refid)/*[@express_attribute_name = 'coordinates']/p28:list_literal/*"/>
    <xsl:if test="($axis and not($axis[1] = 0 and $axis[2] = 0 and $axis[3] &gt; 0)) or ($ref and $ref[3] != 0)">
      <xsl:message terminate="yes"><xsl:value-of select="concat('p28-raw-demo handles placements that turn about +Z only, and #', substring-after($placement/@id, 'Id'), ' tilts the axis')"/></xsl:message>
    </xsl:if>
    <xsl:variable name="n" select="math:sqrt($ref[1] * $ref[1] + $ref[2] * $ref[2])"/>
    <xsl:choose>
      <xsl:when test="$what = 'a' and not($ref)">1</xsl:when>
      <xsl:when test="$what = 'b' and not($ref)">0</xsl:when>
      <xsl:when test="$what = 'a'"><xsl:value-of select="$ref[1] div $n"/></xsl:when>
      <xsl:when test="$what = 'b'"><xsl:value-of select="$ref[2] div $n"/></xsl:when>
      <xsl:when test="not($loc)">0</xsl:when>
      <xsl:when test="$what = 'x'"><xsl:value-of select="number($loc[1])"/></xsl:when>
      <xsl:when test="$what = 'y'"><xsl:value-of select="number($loc[2])"/></xsl:when>
      <xsl:otherwise><xsl:value-of select="number($loc[3])"/></xsl:otherwise>
    </xsl:choose>
  </xsl:template>

  <xsl:template name="block">
    <xsl:param name="text"/>
    <xsl:value-of select="ext:line(concat('N', ext:block(), ' ', $text))"/>
    <xsl:text>&#10;</xsl:text>
  </xsl:template>
  <xsl:template name="comment">
    <xsl:param name="text"/>
    <xsl:value-of select="concat('(', ext:comment($text), ')')"/>
    <xsl:text>&#10;</xsl:text>
  </xsl:template>

  <xsl:template match="/">
    <xsl:if test="not(p28:iso_10303_28/p28:data_section)">
      <xsl:message terminate="yes">p28-raw-demo reads a late-bound ISO 10303-28 document (iso_10303_28 / data_section) and found none</xsl:message>
    </xsl:if>
    <xsl:if test="count($project) != 1">
      <xsl:message terminate="yes">p28-raw-demo needs exactly one PROJECT instance</xsl:message>
    </xsl:if>
    <xsl:if test="not($plan/@express_entity_name = 'workplan')">
      <xsl:message terminate="yes">p28-raw-demo handles a main workplan that is a WORKPLAN only</xsl:message>
    </xsl:if>
    <xsl:variable name="elements" select="key('id', $plan/p28:attribute_instance[@express_attribute_name = 'its_elements']/p28:list_literal/p28:entity_instance_ref/@refid)"/>
    <xsl:if test="not($elements/*[@express_attribute_name = 'its_toolpath'] | key('id', $elements/*[@express_attribute_name = 'its_operation']/p28:entity_instance_ref/@refid)/*[@express_attribute_name = 'its_toolpath'])">
      <xsl:message terminate="yes">p28-raw-demo writes explicit toolpaths only, and no workingstep of the main workplan has one</xsl:message>
    </xsl:if>
    <xsl:text>%&#10;</xsl:text>
    <xsl:call-template name="comment">
      <xsl:with-param name="text" select="concat('PROJECT #', substring-after($project/@id, 'Id'), ' ', $project/*[@express_attribute_name = 'its_id']//p28:string_literal)"/>
    </xsl:call-template>
    <xsl:call-template name="block"><xsl:with-param name="text" select="'G21 G17 G90 G94 G40 G49 G80'"/></xsl:call-template>
    <!-- key() returns document order; the workplan's order is the list's. -->
    <xsl:for-each select="$plan/p28:attribute_instance[@express_attribute_name = 'its_elements']/p28:list_literal/p28:entity_instance_ref">
      <xsl:apply-templates select="key('id', @refid)" mode="executable"/>
    </xsl:for-each>
    <xsl:call-template name="block"><xsl:with-param name="text" select="'M5'"/></xsl:call-template>
    <xsl:call-template name="block"><xsl:with-param name="text" select="'M2'"/></xsl:call-template>
    <xsl:text>%&#10;</xsl:text>
  </xsl:template>

  <xsl:template match="p28:entity_instance" mode="executable">
    <xsl:call-template name="comment">
      <xsl:with-param name="text" select="concat('WS #', substring-after(@id, 'Id'), ' ', *[@express_attribute_name = 'its_id']//p28:string_literal, ' - ', @express_entity_name, ' not handled by this demo')"/>
    </xsl:call-template>
  </xsl:template>

  <!-- A workingstep with an operation that carries a toolpath, or a rapid movement. -->
  <xsl:template match="p28:entity_instance[@express_entity_name = 'machining_workingstep' or @express_entity_name = 'rapid_movement']" mode="executable">
    <xsl:variable name="op" select="key('id', *[@express_attribute_name = 'its_operation']/p28:entity_instance_ref/@refid)"/>
    <xsl:variable name="carrier" select="self::*[@express_entity_name = 'rapid_movement'] | $op"/>
    <xsl:variable name="rapid" select="@express_entity_name = 'rapid_movement'"/>
    <xsl:call-template name="comment">
      <xsl:with-param name="text" select="concat('WS #', substring-after(@id, 'Id'), ' ', *[@express_attribute_name = 'its_id']//p28:string_literal)"/>
    </xsl:call-template>
    <xsl:variable name="tool" select="key('id', $op/*[@express_attribute_name = 'its_tool']/p28:entity_instance_ref/@refid)"/>
    <xsl:if test="$tool">
      <xsl:call-template name="comment"><xsl:with-param name="text" select="concat('TOOL ', $tool/*[@express_attribute_name = 'its_id']//p28:string_literal)"/></xsl:call-template>
    </xsl:if>
    <xsl:call-template name="technology">
      <xsl:with-param name="tech" select="key('id', $op/*[@express_attribute_name = 'its_technology']/p28:entity_instance_ref/@refid)"/>
    </xsl:call-template>
    <!-- Toolpaths are in the feature's placement, in the workpiece set-up of the feature's
         workpiece, in the set-up (a rapid movement: in the first workpiece set-up). -->
    <xsl:variable name="feature" select="key('id', *[@express_attribute_name = 'its_feature']/p28:entity_instance_ref/@refid)"/>
    <xsl:variable name="wps" select="($workpiece_setups[*[@express_attribute_name = 'its_workpiece']/p28:entity_instance_ref/@refid = $feature/*[@express_attribute_name = 'its_workpiece']/p28:entity_instance_ref/@refid] | $workpiece_setups[not($feature)][1])[1]"/>
    <xsl:variable name="p1" select="key('id', $setup/*[@express_attribute_name = 'its_origin']/p28:entity_instance_ref/@refid)"/>
    <xsl:variable name="p2" select="key('id', $wps/*[@express_attribute_name = 'its_origin']/p28:entity_instance_ref/@refid)"/>
    <xsl:variable name="p3" select="key('id', $feature/*[@express_attribute_name = 'feature_placement']/p28:entity_instance_ref/@refid)"/>
    <xsl:variable name="a1"><xsl:call-template name="placement"><xsl:with-param name="placement" select="$p1"/><xsl:with-param name="what" select="'a'"/></xsl:call-template></xsl:variable>
    <xsl:variable name="b1"><xsl:call-template name="placement"><xsl:with-param name="placement" select="$p1"/><xsl:with-param name="what" select="'b'"/></xsl:call-template></xsl:variable>
    <xsl:variable name="x1"><xsl:call-template name="placement"><xsl:with-param name="placement" select="$p1"/><xsl:with-param name="what" select="'x'"/></xsl:call-template></xsl:variable>
    <xsl:variable name="y1"><xsl:call-template name="placement"><xsl:with-param name="placement" select="$p1"/><xsl:with-param name="what" select="'y'"/></xsl:call-template></xsl:variable>
    <xsl:variable name="z1"><xsl:call-template name="placement"><xsl:with-param name="placement" select="$p1"/><xsl:with-param name="what" select="'z'"/></xsl:call-template></xsl:variable>
    <xsl:variable name="a2"><xsl:call-template name="placement"><xsl:with-param name="placement" select="$p2"/><xsl:with-param name="what" select="'a'"/></xsl:call-template></xsl:variable>
    <xsl:variable name="b2"><xsl:call-template name="placement"><xsl:with-param name="placement" select="$p2"/><xsl:with-param name="what" select="'b'"/></xsl:call-template></xsl:variable>
    <xsl:variable name="x2"><xsl:call-template name="placement"><xsl:with-param name="placement" select="$p2"/><xsl:with-param name="what" select="'x'"/></xsl:call-template></xsl:variable>
    <xsl:variable name="y2"><xsl:call-template name="placement"><xsl:with-param name="placement" select="$p2"/><xsl:with-param name="what" select="'y'"/></xsl:call-template></xsl:variable>
    <xsl:variable name="z2"><xsl:call-template name="placement"><xsl:with-param name="placement" select="$p2"/><xsl:with-param name="what" select="'z'"/></xsl:call-template></xsl:variable>
    <xsl:variable name="a3"><xsl:call-template name="placement"><xsl:with-param name="placement" select="$p3"/><xsl:with-param name="what" select="'a'"/></xsl:call-template></xsl:variable>
    <xsl:variable name="b3"><xsl:call-template name="placement"><xsl:with-param name="placement" select="$p3"/><xsl:with-param name="what" select="'b'"/></xsl:call-template></xsl:variable>
    <xsl:variable name="x3"><xsl:call-template name="placement"><xsl:with-param name="placement" select="$p3"/><xsl:with-param name="what" select="'x'"/></xsl:call-template></xsl:variable>
    <xsl:variable name="y3"><xsl:call-template name="placement"><xsl:with-param name="placement" select="$p3"/><xsl:with-param name="what" select="'y'"/></xsl:call-template></xsl:variable>
    <xsl:variable name="z3"><xsl:call-template name="placement"><xsl:with-param name="placement" select="$p3"/><xsl:with-param name="what" select="'z'"/></xsl:call-template></xsl:variable>
    <!-- Setup ∘ workpiece set-up ∘ feature: rotations about Z multiply as complex numbers. -->
    <xsl:variable name="a12" select="$a1 * $a2 - $b1 * $b2"/>
    <xsl:variable name="b12" select="$a1 * $b2 + $b1 * $a2"/>
    <xsl:variable name="ra" select="$a12 * $a3 - $b12 * $b3"/>
    <xsl:variable name="rb" select="$a12 * $b3 + $b12 * $a3"/>
    <xsl:variable name="dx" select="$a12 * $x3 - $b12 * $y3 + $a1 * $x2 - $b1 * $y2 + $x1"/>
    <xsl:variable name="dy" select="$a12 * $y3 + $b12 * $x3 + $a1 * $y2 + $b1 * $x2 + $y1"/>
    <xsl:variable name="dz" select="$z1 + $z2 + $z3"/>
    <xsl:variable name="list" select="key('id', $carrier/*[@express_attribute_name = 'its_toolpath']/p28:entity_instance_ref/@refid)"/>
    <xsl:if test="not($list)">
      <xsl:call-template name="comment"><xsl:with-param name="text" select="'no explicit toolpath - not handled by this demo'"/></xsl:call-template>
    </xsl:if>
    <xsl:for-each select="$list/*[@express_attribute_name = 'its_list']/p28:list_literal/p28:entity_instance_ref">
      <xsl:variable name="path" select="key('id', @refid)"/>
      <xsl:call-template name="technology">
        <xsl:with-param name="tech" select="key('id', $path/*[@express_attribute_name = 'its_technology']/p28:entity_instance_ref/@refid)"/>
      </xsl:call-template>
      <xsl:variable name="curve" select="key('id', $path/*[@express_attribute_name = 'basiccurve']/p28:entity_instance_ref/@refid)"/>
      <xsl:choose>
        <xsl:when test="$path/@express_entity_name = 'cutter_location_trajectory' and $curve/@express_entity_name = 'polyline'">
          <xsl:for-each select="$curve/*[@express_attribute_name = 'points']/p28:list_literal/p28:entity_instance_ref">
            <xsl:variable name="c" select="key('id', @refid)/*[@express_attribute_name = 'coordinates']/p28:list_literal/*"/>
            <xsl:variable name="x" select="$ra * $c[1] - $rb * $c[2] + $dx"/>
            <xsl:variable name="y" select="$rb * $c[1] + $ra * $c[2] + $dy"/>
            <xsl:variable name="z" select="$c[3] + $dz"/>
            <xsl:call-template name="block">
              <xsl:with-param name="text" select="concat(substring('G1G0', 1 + 2 * $rapid, 2),
                  ' X', ext:format(ext:setup-x($x, $y, $z), 'length'),
                  ' Y', ext:format(ext:setup-y($x, $y, $z), 'length'),
                  ' Z', ext:format(ext:setup-z($x, $y, $z), 'length'))"/>
            </xsl:call-template>
          </xsl:for-each>
        </xsl:when>
        <xsl:otherwise>
          <xsl:call-template name="comment">
            <xsl:with-param name="text" select="concat('SKIPPED toolpath #', substring-after($path/@id, 'Id'), ' ', $path/@express_entity_name, ' of ', $curve/@express_entity_name, ' - not handled by this demo')"/>
          </xsl:call-template>
        </xsl:otherwise>
      </xsl:choose>
    </xsl:for-each>
  </xsl:template>

  <!-- ISO 14649 units: feed in m/s (x 60000: mm/min), spindle in rev/s (x 60: rpm; negative
       is clockwise, M3). -->
  <xsl:template name="technology">
    <xsl:param name="tech"/>
    <xsl:variable name="feed" select="$tech/*[@express_attribute_name = 'feedrate']//p28:real_literal"/>
    <xsl:variable name="spindle" select="$tech/*[@express_attribute_name = 'spindle']//p28:real_literal"/>
    <xsl:if test="$feed">
      <xsl:call-template name="block"><xsl:with-param name="text" select="concat('F', ext:format($feed * 60000, 'feed'))"/></xsl:call-template>
    </xsl:if>
    <xsl:if test="$spindle">
      <xsl:call-template name="block">
        <xsl:with-param name="text" select="concat('S', ext:format(60 * ($spindle * ($spindle &gt;= 0) - $spindle * ($spindle &lt; 0)), 'speed'), substring(' M3 M4', 1 + 3 * ($spindle &gt;= 0), 3))"/>
      </xsl:call-template>
    </xsl:if>
  </xsl:template>
</xsl:stylesheet>
