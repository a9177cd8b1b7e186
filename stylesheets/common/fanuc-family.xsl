<?xml version="1.0" encoding="UTF-8"?>
<!-- The FANUC family of controllers (FANUC, Haas, Mitsubishi): "%", O number, optional N block
     numbers (ext:block), R arcs when the sweep allows it (the profile's capabilities.arcs), native
     drilling cycles G81/G82/G83/G73/G84/G74/G85/G86/G89 with G98 (return to the initial level)
     or G99 (R level) and G80, M30, "%". N block numbers when the member's profile.json says
     block_numbers.numbered. A member's post.xsl imports this and sets:
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

  <!-- R for arcs of less than a full turn in the XY plane when the profile says arcs: r
       (ext:arc-words); I, J, K otherwise. -->
  <xsl:variable name="arc_form" select="$arcs"/>

  <!-- Dwell: G4 with the family member's word; its units come from the profile's dwell format
       (FANUC: P in milliseconds; Haas: P in seconds with a point; Mitsubishi: X in seconds). -->
  <xsl:template match="DWELL">
    <xsl:value-of select="ext:block-line(concat('G4 ', $dwell_word, ext:format(@seconds, 'dwell')))"/><xsl:text>&#10;</xsl:text>
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
    <xsl:value-of select="ext:block-line(concat('G0', $safe))"/><xsl:text>&#10;</xsl:text>
    <xsl:variable name="q">
      <xsl:if test="self::PECK_DRILL_CYCLE"><xsl:value-of select="concat(' Q', ext:format(@peck, 'length'))"/></xsl:if>
    </xsl:variable>
    <xsl:variable name="p">
      <xsl:if test="@dwell &gt; 0"><xsl:value-of select="concat(' P', ext:format(@dwell, 'dwell'))"/></xsl:if>
    </xsl:variable>
    <xsl:value-of select="ext:block-line(concat($return, ' ', $code,
        ' X', ext:format(ext:setup-x(@x, @y, @bottom_z), 'length'),
        ' Y', ext:format(ext:setup-y(@x, @y, @bottom_z), 'length'),
        ' Z', ext:format(ext:setup-z(@x, @y, @bottom_z), 'length'),
        ' R', ext:format(ext:setup-z(@x, @y, @r_z), 'length'), $q, $p,
        ' F', ext:format(@feed, 'feed')))"/>
    <xsl:text>&#10;</xsl:text>
    <xsl:value-of select="ext:block-line('G80')"/><xsl:text>&#10;</xsl:text>
    <xsl:value-of select="ext:moved-to(@x, @y, @safe_z)"/>
  </xsl:template>

  <xsl:template match="PROGRAM_END">
    <xsl:value-of select="ext:block-line('M30')"/><xsl:text>&#10;</xsl:text>
  </xsl:template>
  <xsl:template match="PROJECT_END"><xsl:text>%&#10;</xsl:text></xsl:template>
</xsl:stylesheet>
