<?xml version="1.0" encoding="UTF-8"?>
<!-- The FANUC family of controllers (FANUC, Haas, Mitsubishi): "%", O number, optional N block
     numbers (ext:block), R arcs when the sweep allows it (the profile's capabilities.arcs), native
     drilling cycles G81/G82/G83/G73/G84/G74/G85/G86/G89 with G98 (return to the initial level)
     or G99 (R level) and G80, M30, "%". A member's post.xsl imports this and sets:
       $numbered     'yes' or 'no': N block numbers
       $o_padding    zeros the O number is padded to ('0000' for O0001)
       $dwell_word   the G4 address, 'P' or 'X' -->
<xsl:stylesheet version="1.0" xmlns:xsl="http://www.w3.org/1999/XSL/Transform"
    xmlns:ext="urn:ncpost:ext" exclude-result-prefixes="ext">
  <xsl:import href="ncpost-common.xsl"/>
  <xsl:output method="text" encoding="UTF-8"/>
  <xsl:variable name="o_padding" select="'0000'"/>
  <xsl:variable name="dwell_word" select="'P'"/>


  <xsl:template match="PROJECT_BEGIN">
    <xsl:text>%&#10;</xsl:text>
    <xsl:value-of select="concat('O', substring($o_padding, string-length($program_number) + 1), $program_number,
                                 ' (', ext:comment(@name), ')')"/>
    <xsl:text>&#10;</xsl:text>
    <xsl:variable name="units">
      <xsl:choose><xsl:when test="ext:units() = 'inch'">G20</xsl:when><xsl:otherwise>G21</xsl:otherwise></xsl:choose>
    </xsl:variable>
    <xsl:value-of select="substring(ext:modal('plane', 'G17'), 1, 0)"/>
    <xsl:call-template name="block">
      <xsl:with-param name="text" select="concat($units, ' G17 G90 G94 G40 G49 G80')"/>
    </xsl:call-template>
  </xsl:template>

  <!-- R for arcs of less than a full turn when the profile says arcs: r; IJK otherwise. -->
  <xsl:template name="arc-centre">
    <xsl:variable name="sx" select="ext:position('x')"/>
    <xsl:variable name="sy" select="ext:position('y')"/>
    <xsl:choose>
      <xsl:when test="$arcs = 'r' and @plane = 'xy' and (@rotation = 1 or @rotation = -1) and
                      ext:arc-sweep($sx, $sy, @x, @y, @cx, @cy, @rotation) &lt; 359.999 and
                      ext:arc-sweep($sx, $sy, @x, @y, @cx, @cy, @rotation) &gt; -359.999">
        <xsl:value-of select="concat(' R', ext:format(ext:arc-r($sx, $sy, @x, @y, @cx, @cy, @rotation), 'length'))"/>
      </xsl:when>
      <xsl:otherwise><xsl:call-template name="arc-ijk"/></xsl:otherwise>
    </xsl:choose>
  </xsl:template>
  <!-- ARC_FEED as in ncpost-common.xsl (inline, no result-tree fragments), with the R form of
       "arc-centre" above. -->
  <xsl:template match="ARC_FEED">
    <xsl:if test="not(@plane)">
      <xsl:message terminate="yes">ARC_FEED in a tilted plane has no G2/G3 form on this controller</xsl:message>
    </xsl:if>
    <!-- 0: xy (or none), 1: yz, 2: xz -->
    <xsl:variable name="pl" select="(@plane = 'yz') + 2 * (@plane = 'xz')"/>
    <xsl:variable name="plane" select="ext:modal('plane', substring('G17G19G18', 1 + 3 * $pl, 3))"/>
    <xsl:if test="$plane != ''">
      <xsl:call-template name="block"><xsl:with-param name="text" select="$plane"/></xsl:call-template>
    </xsl:if>
    <xsl:choose>
      <xsl:when test="@a or @b or @c">
        <xsl:call-template name="arc-general"/>
      </xsl:when>
      <xsl:otherwise>
        <xsl:variable name="x" select="number(@x)"/>
        <xsl:variable name="y" select="number(@y)"/>
        <xsl:variable name="z" select="number(@z)"/>
        <xsl:variable name="cx" select="number(@cx)"/>
        <xsl:variable name="cy" select="number(@cy)"/>
        <xsl:variable name="cz" select="number(@cz)"/>
        <xsl:variable name="axes" select="concat(substring('G2G3', 1 + 2 * (@rotation &gt; 0), 2),
                       ' X', ext:format(ext:setup-x($x, $y, $z), 'length'),
                       ' Y', ext:format(ext:setup-y($x, $y, $z), 'length'),
                       ' Z', ext:format(ext:setup-z($x, $y, $z), 'length'))"/>
        <xsl:variable name="sx" select="ext:position('x')"/>
        <xsl:variable name="sy" select="ext:position('y')"/>
        <xsl:choose>
          <xsl:when test="$arcs = 'r' and @plane = 'xy' and (@rotation = 1 or @rotation = -1) and
                          ext:arc-sweep($sx, $sy, $x, $y, $cx, $cy, @rotation) &lt; 359.999 and
                          ext:arc-sweep($sx, $sy, $x, $y, $cx, $cy, @rotation) &gt; -359.999">
            <xsl:variable name="text" select="concat($axes, ' R', ext:format(ext:arc-r($sx, $sy, $x, $y, $cx, $cy, @rotation), 'length'))"/>
            <xsl:choose>
              <xsl:when test="$numbered = 'yes'">
                <xsl:value-of select="concat(ext:line(concat('N', ext:block(), ' ', $text)), '&#10;', ext:moved-to($x, $y, $z))"/>
              </xsl:when>
              <xsl:otherwise>
                <xsl:value-of select="concat(ext:line($text), '&#10;', ext:moved-to($x, $y, $z))"/>
              </xsl:otherwise>
            </xsl:choose>
          </xsl:when>
          <xsl:otherwise>
            <xsl:variable name="sz" select="ext:position('z')"/>
            <xsl:variable name="text" select="concat($axes,
                substring(concat(' I', ext:format(ext:arc-i(ext:setup-x($sx, $sy, $sz), ext:setup-x($cx, $cy, $cz)), 'length')), 1, 1000 * ($pl != 1)),
                substring(concat(' J', ext:format(ext:arc-j(ext:setup-y($sx, $sy, $sz), ext:setup-y($cx, $cy, $cz)), 'length')), 1, 1000 * ($pl != 2)),
                substring(concat(' K', ext:format(ext:arc-k(ext:setup-z($sx, $sy, $sz), ext:setup-z($cx, $cy, $cz)), 'length')), 1, 1000 * ($pl != 0)),
                substring(concat(' P', translate(@rotation, '-', '')), 1, 1000 * (@rotation &gt; 1 or @rotation &lt; -1)))"/>
            <xsl:choose>
              <xsl:when test="$numbered = 'yes'">
                <xsl:value-of select="concat(ext:line(concat('N', ext:block(), ' ', $text)), '&#10;', ext:moved-to($x, $y, $z))"/>
              </xsl:when>
              <xsl:otherwise>
                <xsl:value-of select="concat(ext:line($text), '&#10;', ext:moved-to($x, $y, $z))"/>
              </xsl:otherwise>
            </xsl:choose>
          </xsl:otherwise>
        </xsl:choose>
      </xsl:otherwise>
    </xsl:choose>
  </xsl:template>

  <!-- Dwell: G4 with the family member's word; its units come from the profile's dwell format
       (FANUC: P in milliseconds; Haas: P in seconds with a point; Mitsubishi: X in seconds). -->
  <xsl:template match="DWELL">
    <xsl:call-template name="block"><xsl:with-param name="text" select="concat('G4 ', $dwell_word, ext:format(@seconds, 'dwell'))"/></xsl:call-template>
  </xsl:template>

  <!-- Cycles: G0 to the safe level over the hole, then the cycle with G98 (return to the
       initial level = safe_z), or G99 when safe_z = r_z, then G80. -->
  <xsl:template match="DRILL_CYCLE | PECK_DRILL_CYCLE | TAP_CYCLE | BORE_CYCLE | REAM_CYCLE">
    <xsl:variable name="code">
      <xsl:choose>
        <xsl:when test="self::DRILL_CYCLE and @dwell &gt; 0">G82</xsl:when>
        <xsl:when test="self::DRILL_CYCLE">G81</xsl:when>
        <xsl:when test="self::PECK_DRILL_CYCLE and @peck_retract &gt; 0">G73</xsl:when>
        <xsl:when test="self::PECK_DRILL_CYCLE">G83</xsl:when>
        <xsl:when test="self::TAP_CYCLE and @hand = 'left'">G74</xsl:when>
        <xsl:when test="self::TAP_CYCLE">G84</xsl:when>
        <xsl:when test="self::BORE_CYCLE and @spindle_stop = 'true'">G86</xsl:when>
        <xsl:when test="@dwell &gt; 0">G89</xsl:when>
        <xsl:otherwise>G85</xsl:otherwise>
      </xsl:choose>
    </xsl:variable>
    <xsl:variable name="return">
      <xsl:choose><xsl:when test="@safe_z = @r_z">G99</xsl:when><xsl:otherwise>G98</xsl:otherwise></xsl:choose>
    </xsl:variable>
    <xsl:variable name="safe"><xsl:call-template name="xyz"><xsl:with-param name="z" select="@safe_z"/></xsl:call-template></xsl:variable>
    <xsl:call-template name="block"><xsl:with-param name="text" select="concat('G0', $safe)"/></xsl:call-template>
    <xsl:variable name="q">
      <xsl:if test="self::PECK_DRILL_CYCLE"><xsl:value-of select="concat(' Q', ext:format(@peck, 'length'))"/></xsl:if>
    </xsl:variable>
    <xsl:variable name="p">
      <xsl:if test="@dwell &gt; 0"><xsl:value-of select="concat(' P', ext:format(@dwell, 'dwell'))"/></xsl:if>
    </xsl:variable>
    <xsl:call-template name="block">
      <xsl:with-param name="text" select="concat($return, ' ', $code,
          ' X', ext:format(ext:setup-x(@x, @y, @bottom_z), 'length'),
          ' Y', ext:format(ext:setup-y(@x, @y, @bottom_z), 'length'),
          ' Z', ext:format(ext:setup-z(@x, @y, @bottom_z), 'length'),
          ' R', ext:format(ext:setup-z(@x, @y, @r_z), 'length'), $q, $p,
          ' F', ext:format(@feed, 'feed'))"/>
    </xsl:call-template>
    <xsl:call-template name="block"><xsl:with-param name="text" select="'G80'"/></xsl:call-template>
    <xsl:value-of select="ext:moved-to(@x, @y, @safe_z)"/>
  </xsl:template>

  <xsl:template match="PROGRAM_END">
    <xsl:call-template name="block"><xsl:with-param name="text" select="'M30'"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="PROJECT_END"><xsl:text>%&#10;</xsl:text></xsl:template>
</xsl:stylesheet>
