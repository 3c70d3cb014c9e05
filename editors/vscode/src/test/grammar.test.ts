// The TextMate grammar, tokenised by VS Code's own engine (vscode-textmate with the Oniguruma regexes it uses).
import * as assert from "node:assert/strict";
import * as fs from "node:fs";
import * as path from "node:path";
import { before, test } from "node:test";
import * as oniguruma from "vscode-oniguruma";
import * as textmate from "vscode-textmate";

const root = path.join(__dirname, "..", "..");
let grammar: textmate.IGrammar;
let lines: string[];
let tokens: { text: string; scopes: string[] }[][];

before(async () => {
  const wasm = fs.readFileSync(path.join(root, "node_modules", "vscode-oniguruma", "release", "onig.wasm"));
  await oniguruma.loadWASM(wasm.buffer.slice(wasm.byteOffset, wasm.byteOffset + wasm.byteLength));
  const registry = new textmate.Registry({
    onigLib: Promise.resolve({
      createOnigScanner: (sources: string[]) => new oniguruma.OnigScanner(sources),
      createOnigString: (s: string) => new oniguruma.OnigString(s),
    }),
    loadGrammar: async (scopeName: string) => {
      if (scopeName !== "source.rrf-gcode") {
        return null;
      }
      const file = path.join(root, "syntaxes", "rrf-gcode.tmLanguage.json");
      return textmate.parseRawGrammar(fs.readFileSync(file, "utf8"), file);
    },
  });
  const loaded = await registry.loadGrammar("source.rrf-gcode");
  assert.ok(loaded, "the grammar loads");
  grammar = loaded;
  lines = fs.readFileSync(path.join(root, "test", "sample.g"), "utf8").split("\n");
  let stack = textmate.INITIAL;
  tokens = lines.map((line) => {
    const r = grammar.tokenizeLine(line, stack);
    stack = r.ruleStack;
    return r.tokens.map((t) => ({ text: line.slice(t.startIndex, t.endIndex), scopes: t.scopes }));
  });
});

/** The scope list of the token that is exactly `text` on the line that starts with `prefix`. */
function scopes(prefix: string, text: string, nth = 0): string[] {
  const i = lines.findIndex((l) => l.trimStart().startsWith(prefix));
  assert.ok(i >= 0, `no line starts with ${prefix}`);
  const found = tokens[i].filter((t) => t.text === text);
  assert.ok(found.length > nth, `no token '${text}' on line ${i + 1}: ${JSON.stringify(tokens[i])}`);
  return found[nth].scopes;
}

function has(prefix: string, text: string, scope: string, nth = 0): void {
  const s = scopes(prefix, text, nth);
  assert.ok(s.includes(scope), `'${text}' on '${prefix}…' has ${s.join(" ")}, not ${scope}`);
}

test("comments: ; to the end of the line, and ( … ) in a command", () => {
  has("; sample", "; sample RRF G-code for the grammar test".slice(1), "comment.line.semicolon.rrf-gcode");
  has("N10", " move", "comment.line.semicolon.rrf-gcode");
  has("G28", "(home all)", "comment.block.parenthesis.rrf-gcode");
  has("G28", "X", "variable.parameter.rrf-gcode");
});

test("commands, line numbers, parameter letters and numbers", () => {
  has("N10", "N10", "constant.other.line-number.rrf-gcode");
  has("N10", "G1", "support.function.gcode.rrf-gcode");
  has("N10", "X", "variable.parameter.rrf-gcode");
  has("N10", "10.5", "constant.numeric.rrf-gcode");
  has("N10", "-2", "constant.numeric.rrf-gcode");
  has("M584", "M584", "support.function.mcode.rrf-gcode");
  has("M584", ":", "punctuation.separator.list.rrf-gcode");
  has("M584", "0.1", "constant.numeric.rrf-gcode");
  has("T-1", "T-1", "support.function.tcode.rrf-gcode");
  // After the command, T is a parameter (M308's thermistor resistance), not a tool change.
  has("M308", "T", "variable.parameter.rrf-gcode");
  has("M308", "100000", "constant.numeric.rrf-gcode");
  // An unquoted G or M ends a command and starts the next one, as in the firmware's parser.
  has("G53", "G1", "support.function.gcode.rrf-gcode");
  has("G53", "Z", "variable.parameter.rrf-gcode");
  has("G53", "M400", "support.function.mcode.rrf-gcode");
});

test('strings, with "" for a quote', () => {
  has("M550", '"', "string.quoted.double.rrf-gcode");
  has("M550", '""', "constant.character.escape.quote.rrf-gcode");
  has("M550", "Duet", "string.quoted.double.rrf-gcode");
  has("M550", " printer", "string.quoted.double.rrf-gcode");
  // The string ends at its closing quote: nothing after it is part of the string.
  const last = scopes("M550", '"', 1);
  assert.ok(last.includes("punctuation.definition.string.end.rrf-gcode"), last.join(" "));
});

test("{ } expressions inside a command", () => {
  has("N10", "{", "punctuation.section.expression.begin.rrf-gcode");
  has("N10", "global", "variable.language.global.rrf-gcode");
  has("N10", "speed", "variable.other.global.rrf-gcode");
  has("N10", "*", "keyword.operator.rrf-gcode");
  has("N10", "60", "meta.expression.rrf-gcode");
  has("N10", "}", "punctuation.section.expression.end.rrf-gcode");
});

test("meta-commands", () => {
  has("if ", "if", "keyword.control.if.rrf-gcode");
  has("if ", "move", "variable.other.object-model.rrf-gcode");
  has("if ", "&&", "keyword.operator.rrf-gcode");
  has("if ", "exists", "support.function.builtin.rrf-gcode");
  has("var ", "var", "storage.type.var.rrf-gcode");
  has("var ", "offset", "variable.other.definition.rrf-gcode");
  has("var ", "S", "variable.other.param.rrf-gcode");
  has("var ", "1.5e-1", "constant.numeric.rrf-gcode");
  has("elif", "elif", "keyword.control.elif.rrf-gcode");
  has("elif", "fileexists", "support.function.builtin.rrf-gcode");
  has("set ", "set", "keyword.other.set.rrf-gcode");
  has("set ", "offset", "variable.other.var.rrf-gcode");
  has("else", "else", "keyword.control.else.rrf-gcode");
  has("echo", "echo", "keyword.other.echo.rrf-gcode");
  has("echo", ">>", "keyword.operator.redirect.rrf-gcode");
  has("echo", "pi", "constant.language.rrf-gcode");
  has("while", "while", "keyword.control.while.rrf-gcode");
  has("while", "iterations", "constant.language.rrf-gcode");
  has("break", "break", "keyword.control.break.rrf-gcode");
  has("abort", "abort", "keyword.control.abort.rrf-gcode");
  has("global ", "global", "storage.type.global.rrf-gcode");
  has("global ", "0x1F", "constant.numeric.rrf-gcode");
});

test("an unterminated string or brace does not run into the next line", () => {
  let stack = textmate.INITIAL;
  for (const line of ['M117 "open', "M118 {1 + "]) {
    stack = grammar.tokenizeLine(line, stack).ruleStack;
  }
  const next = grammar.tokenizeLine("G1 X1", stack).tokens;
  const g1 = next.find((t) => t.startIndex === 0);
  assert.ok(g1 && g1.scopes.includes("support.function.gcode.rrf-gcode"), JSON.stringify(next));
});
