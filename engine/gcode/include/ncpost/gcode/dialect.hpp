#pragma once
// A controller's reading rules, as stylesheets/<profile-id>/dialect.json states them (schema:
// stylesheets/dialect.schema.json, field by field in docs/gcode.md). In: the JSON text
// (load_dialect in gcode.hpp). Out: this value, checked, shared read-only by every read.
//
// The grammar features (comments, expressions, parameters, control statements) are code that
// a dialect switches on and spells; what the words and the G/M codes mean is data: each code
// names an action the converter knows ("rapid", "cycle", "work_offset", ...), its modal group,
// the words it requires and allows. A new dialect is a new file, not a new build.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace ncpost::gcode {

// Word-address G-code (ISO 6983 and its relatives: LinuxCNC, FANUC, Sinumerik, ...), or
// Heidenhain's conversational Klartext.
enum class Syntax : std::uint8_t { WordAddress, Klartext };

// A word's name: the letters A..Z are 0..25; multi-letter words a dialect declares (Sinumerik
// `CR=`, `TURN=`) follow from 26 on.
using WordId = std::uint8_t;
inline constexpr WordId kNoWord = 0xff;
inline constexpr std::size_t kMaxWords = 64;
[[nodiscard]] constexpr WordId letter_word(char upper) noexcept {
  return static_cast<WordId>(upper - 'A');
}

// What a word's value is, which decides how a plain integer literal reads and which values are
// valid.
enum class WordKind : std::uint8_t {
  Axis,         // a coordinate (X Y Z A B C U V W): least-increment scaling applies
  Length,       // another length (I J K R Q ...): least-increment scaling applies
  Number,       // any number (P, L, D, H, ...)
  Feed,         // F
  Speed,        // S
  Tool,         // T: a non-negative integer
  GCode,        // G
  MCode,        // M
  LineNumber,   // N
  Program,      // O (a program number or, in LinuxCNC, an O-word statement)
  PolarRadius,  // LinuxCNC @: distance from the origin in the XY plane
  PolarAngle,   // LinuxCNC ^: angle from the X axis, degrees
  ToolOffset,   // Sinumerik D: D0 cancels the tool's length offset, D1.. applies it
};

struct WordSpec {
  std::string name;  // "X", "CR"
  WordKind kind = WordKind::Number;
  bool rotary = false;  // A B C: degrees, never scaled to inches
};

// What a G or M code does. The converter implements each; dialect.json names them.
enum class Action : std::uint8_t {
  None,  // read and checked, no effect on the canonical program (path control, overrides)
  Rapid,
  Linear,
  ArcCw,
  ArcCcw,
  Cycle,        // a canned cycle, CodeSpec::cycle says which
  CycleCancel,  // G80
  Dwell,
  PlaneXy,
  PlaneXz,
  PlaneYz,
  UnitsInch,
  UnitsMm,
  Absolute,
  Incremental,
  ArcCentreAbsolute,     // G90.1
  ArcCentreIncremental,  // G91.1
  FeedPerMinute,
  FeedInverseTime,
  FeedPerRevolution,
  WorkOffset,          // G54..: CodeSpec::index (1 = G54), or the P word when index is 0
  WorkOffsetNone,      // Sinumerik G500 (no settable offset)
  MachineCoordinates,  // G53: this block's motion in machine coordinates
  SetCoordinateData,   // G10 (L2/L20: work offsets; tool table forms accepted, no effect)
  AxisOffset,          // G92
  AxisOffsetCancel,    // G92.1, G92.2
  AxisOffsetRestore,   // G92.3
  LocalOffset,         // G52
  Home,                // G28: through the given point to the first reference position
  Home2,               // G30: to the second reference position
  HomeStore,           // G28.1 / G30.1: store the current position (LinuxCNC)
  ToolLengthOffset,    // G43
  ToolLengthCancel,    // G49
  CutterCompOff,       // G40
  RetractInitial,      // G98
  RetractR,            // G99
  SpindleCw,
  SpindleCcw,
  SpindleStop,
  ToolChange,  // M6
  SetTool,     // M61 Q: the tool in the spindle, without a change
  ProgramStop,
  OptionalStop,
  ProgramEnd,
  PalletChange,  // M60: a program stop
  MistOn,
  FloodOn,
  CoolantOff,
  SubprogramCall,     // M98 P.. L..
  LocalCall,          // Haas M97 P..: the subprogram starts at block N.. of this program
  SubprogramReturn,   // M99
  MacroCall,          // G65 P.. L.. with arguments
  Unsupported,        // refused, naming the construct (CodeSpec::refusal)
  Lathe,              // refused: a lathe program (out of scope)
  ArcThroughPoint,    // Sinumerik CIP: a circle through an intermediate point (I1= J1= K1=)
  SplineB,            // Sinumerik BSPLINE: each block a control point (PW= weight, PL= knot step)
  SplineNurbs,        // Mitsubishi/FANUC G06.2: P order, K knots, R weights
  Translate,          // Sinumerik TRANS: a programmable offset replacing the last
  TranslateAdd,       // Sinumerik ATRANS: added to the last
  OnlyWithoutWords,   // accepted alone (a reset such as ROT), refused with words (`refusal`)
  SpindleCwCoolant,   // Heidenhain M13: M3 and M8 at once
  SpindleCcwCoolant,  // Heidenhain M14: M4 and M8 at once
  CycleCall,          // Heidenhain M99: call the cycle defined last (CYCL DEF) here
};

// Which canned cycle a Cycle code is, and where it leaves the hole.
enum class CycleKind : std::uint8_t {
  Drill,       // G81
  DrillDwell,  // G82: dwell at the bottom
  Peck,        // G83: full retract to R between pecks
  ChipBreak,   // G73: short back-off between pecks
  Tap,         // G84
  TapLeft,     // G74
  Bore,        // G85: feed out
  BoreStop,    // G86: spindle stop, rapid out
  BoreDwell,   // G89: dwell, feed out
};

struct CycleSpec {
  CycleKind kind = CycleKind::Drill;
  // Where a feed out (tap, bore) ends: at the R plane, then a rapid to the clearance level
  // (FANUC); or at the clearance level itself (LinuxCNC's G84 and G89).
  bool feed_out_to_clear = false;
};

struct CodeSpec {
  std::string text;  // "G38.2", "M98": for messages
  Action action = Action::None;
  int group = -1;               // index into Dialect::modal_groups; -1: non-modal
  int index = 0;                // WorkOffset: 1 = first work offset (G54); 0: from the index word
  WordId index_word = kNoWord;  // the word that gives the index (P when not said; Okuma H)
  CycleSpec cycle{};
  std::vector<WordId> requires_all;     // every one of these must be in the block
  std::vector<WordId> requires_one_of;  // at least one of these
  std::vector<WordId> allows;           // words this code uses (besides the always-free ones)
  std::string refusal;                  // Unsupported / Lathe: what is refused, by name
  bool warn = false;                    // accepted without effect, with a warning (first use)
  // Planes a motion code is converted in (bits: 1 XY, 2 XZ, 4 YZ); in another it is refused,
  // `refusal` saying why.
  std::uint8_t planes = 7;
};

// How parameters (variables) are written and what an unset one reads as.
enum class ParameterStyle : std::uint8_t {
  None,
  Hash,  // #1, #[expr], ##1; with named_parameters also #<name>
  R,     // R1, R[expr] (Sinumerik arithmetic parameters)
  Q,     // Q1 (Heidenhain)
};

// A range of numbered parameters with a meaning of their own.
enum class ParameterSource : std::uint8_t {
  Machine,          // only the machine knows it: `assumed` value and a warning
  Position,         // current position (axis = number - first), current coordinate system
  MachinePosition,  // current position in machine coordinates
  Tool,             // tool in the spindle
  WorkOffsetIndex,  // 1 = first work offset
  WorkOffsets,      // first + 20 * (n - 1) + axis: work offset n (LinuxCNC #5221...)
  AxisOffsets,      // G92 offset per axis
  Units,            // 0 mm, 1 inch (LinuxCNC #<_metric> style: 1 when metric)
};

struct ParameterRange {
  std::uint32_t first = 0;
  std::uint32_t last = 0;
  ParameterSource source = ParameterSource::Machine;
  std::string name;       // "probe position": named in warnings
  double assumed = 0;     // Machine: the value read
  bool writable = false;  // a program may assign it (LinuxCNC work offsets)
};

struct ParameterRules {
  ParameterStyle style = ParameterStyle::None;
  std::uint32_t count = 0;      // valid numbers are [0, count)
  bool named = false;           // LinuxCNC #<name> / #<_global>
  bool vacant = false;          // FANUC: an unset variable is <vacant> (#0), not 0
  bool zero_read_only = false;  // #0 may not be assigned
  // Sinumerik: assignments take effect one after the other (R1=10 R2=R1*2 gives 20); LinuxCNC
  // and FANUC read the whole block first.
  bool assign_in_order = false;
  std::uint32_t local_first = 0;  // locals of a call (G65 / o-call arguments); 0: none
  std::uint32_t local_last = 0;
  std::vector<ParameterRange> ranges;
  // Named system values: `$AA_IM[Z]`, `#<_hal[...]>`: prefixes of names only the machine knows.
  std::vector<std::string> machine_name_prefixes;
  // FANUC: assigning #3000 stops the program with an alarm; #3006 with a message.
  std::uint32_t alarm = 0;
  std::uint32_t stop_message = 0;
};

// Expression operators. Comparison and logic give 1 or 0.
enum class Operator : std::uint8_t {
  Add,
  Sub,
  Mul,
  Div,
  Mod,
  Pow,
  Eq,
  Ne,
  Gt,
  Ge,
  Lt,
  Le,
  And,
  Or,
  Xor,  // logical: non-zero is true
  BitAnd,
  BitOr,
  BitXor,  // FANUC: on integers
  IntDiv,  // Sinumerik DIV
};

enum class Function : std::uint8_t {
  Sin,
  Cos,
  Tan,
  Asin,
  Acos,
  Atan,
  Atan2,
  Sqrt,
  Abs,
  Round,
  Fix,
  Fup,
  Ln,
  Exp,
  Exists,
  Square,
  Trunc,
  Not,
  Min,
  Max,
  Sign,
  Frac,
  Log10,
  Neg,
  Bin,
  Bcd,
  Away,  // FANUC FUP: away from zero
  Pow,   // two arguments
};

struct OperatorSpec {
  std::string spelling;  // "+", "MOD", "EQ", "=="
  Operator op = Operator::Add;
  int precedence = 0;  // higher binds tighter
};

struct FunctionSpec {
  std::string name;  // "SIN"
  Function function = Function::Sin;
};

struct ExpressionRules {
  char open = '[';
  char close = ']';
  std::vector<OperatorSpec> operators;  // longest spelling first after loading
  std::vector<FunctionSpec> functions;
  bool atan_slash = false;      // ATAN[y]/[x] (LinuxCNC, FANUC)
  bool address_equals = false;  // Sinumerik X=expr, CR=expr
};

// Which control statements a dialect reads (their spelling is fixed by the family).
struct FlowRules {
  bool o_words = false;            // LinuxCNC o<name> sub/call/if/while/do/repeat/...
  bool fanuc_subprograms = false;  // O1234 ... M99 in the file, M98 P1234 (L repeats)
  bool macro_b = false;            // FANUC IF [..] GOTO / THEN, WHILE [..] DO n / END n, GOTO n
  bool sinumerik = false;          // labels, GOTOF/GOTOB, IF/ELSE/ENDIF, WHILE, FOR, REPEAT, LOOP
  bool packed_repeat = false;      // FANUC M98 P30010: repeat 3 times program 0010
  std::vector<std::string> while_spellings;  // "WHILE", "WH"
};

struct ArcRules {
  WordId radius = kNoWord;       // R (FANUC, LinuxCNC), CR (Sinumerik)
  WordId turns = kNoWord;        // P (LinuxCNC), TURN (Sinumerik)
  bool centre_absolute = false;  // I J K absolute unless G91.1 (LinuxCNC starts G91.1)
  bool turns_extra = false;      // the turns word counts extra turns (Sinumerik TURN=1: 2 turns)
  // Radius check of centre-format arcs, LinuxCNC's rule: an arc is wrong when the radii differ
  // by more than absolute * factor, or by more than absolute and relative * the larger radius.
  double tolerance_mm = 0.0;
  double tolerance_inch = 0.0;
  double relative = 0.0;
  double absolute_factor = 100.0;
};

struct CycleRules {
  WordId r_plane = letter_word('R');
  WordId peck = letter_word('Q');
  WordId dwell = letter_word('P');
  WordId repeat = letter_word('L');
  double dwell_scale = 1.0;                                      // P → seconds
  double peck_clearance_mm = 0.254, peck_clearance_inch = 0.01;  // G83 stop above last depth
  double chip_break_mm = 0.254, chip_break_inch = 0.01;          // G73 back-off
  bool clearance_is_machine = false;  // FANUC: the values above are machine parameters
};

struct DwellWord {
  WordId word = kNoWord;
  double scale = 1;          // to seconds: FANUC P 0.001 (ms), X 1
  double integer_scale = 0;  // for a plain integer literal, when it differs (Haas: P1500 is ms,
                             // P1.5 seconds); 0: the same as `scale`
};
struct DwellRules {
  // Words a dwell's time may be in, in order of preference.
  std::vector<DwellWord> words;
};

struct Dialect {
  std::string id;
  std::string name;
  Syntax syntax = Syntax::WordAddress;
  bool metric = true;  // units at the program start

  // Lexical rules.
  bool parenthesis_comments = true;
  bool semicolon_comments = true;
  bool ignore_whitespace = true;  // spaces may stand inside words and numbers (X 1 0 = X10)
  bool block_delete = true;
  bool percent_delimits = true;             // a '%' line starts and ends the program
  bool checksums = false;                   // '*NN' at the end of a block is dropped
  bool integer_literal_increments = false;  // FANUC: X10 = 10 least increments
  double increment_mm = 0.001;
  double increment_inch = 0.0001;
  std::unordered_map<std::string, std::string> comment_commands;  // "MSG," → "message"

  std::vector<WordSpec> words;          // index = WordId
  WordId polar_radius = kNoWord;        // '@' when the dialect reads polar coordinates
  WordId polar_angle = kNoWord;         // '^'
  std::array<bool, 26> letter_known{};  // a letter this dialect reads
  std::vector<std::string> modal_groups;
  std::vector<CodeSpec> codes;        // G and M codes
  std::vector<std::int16_t> g_index;  // G code × 10 → index into codes, -1: none
  std::vector<std::int16_t> m_index;  // M code → index into codes, -1: none
  // Codes spelled as words (Sinumerik CIP, BSPLINE, SUPA, TRANS, DIAMON, ...): name → index into
  // codes, longest name first.
  std::vector<std::pair<std::string, std::int16_t>> keywords;

  ParameterRules parameters;
  ExpressionRules expressions;
  FlowRules flow;
  ArcRules arcs;
  CycleRules cycles;
  DwellRules dwell;

  // Modal state at the program start.
  int initial_motion = -1;  // index into codes (G0/G1/G80), -1: none
  bool initial_retract_r = false;
  std::vector<int> program_end_codes;  // M codes that end the program
  bool require_program_end = true;
  bool missing_end_is_error = false;  // LinuxCNC refuses a file without M2/M30/%
  double assumed_tool_length = 0.0;   // the canonical length of a G43 whose length is unknown

  [[nodiscard]] const CodeSpec* g_code(int code_times_ten) const noexcept {
    if (code_times_ten < 0 || static_cast<std::size_t>(code_times_ten) >= g_index.size())
      return nullptr;
    const auto i = g_index[static_cast<std::size_t>(code_times_ten)];
    return i < 0 ? nullptr : &codes[static_cast<std::size_t>(i)];
  }
  [[nodiscard]] const CodeSpec* m_code(int code) const noexcept {
    if (code < 0 || static_cast<std::size_t>(code) >= m_index.size()) return nullptr;
    const auto i = m_index[static_cast<std::size_t>(code)];
    return i < 0 ? nullptr : &codes[static_cast<std::size_t>(i)];
  }
  // The word of this name (upper case), or kNoWord.
  [[nodiscard]] WordId word(std::string_view name) const noexcept;
};

}  // namespace ncpost::gcode
