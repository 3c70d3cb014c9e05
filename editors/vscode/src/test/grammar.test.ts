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

// The expected scopes are data (test/sample.scopes.json): per topic, [line start, token text or [text, n], scope].
type Row = [string, string | [string, number], string];
const expected = JSON.parse(fs.readFileSync(path.join(root, "test", "sample.scopes.json"), "utf8")) as {
  topics: Record<string, Row[]>;
};

for (const [topic, rows] of Object.entries(expected.topics)) {
  test(topic, () => {
    for (const [prefix, token, scope] of rows) {
      const [text, nth] = typeof token === "string" ? [token, 0] : token;
      has(prefix, text, scope, nth);
    }
  });
}

test("an unterminated string or brace does not run into the next line", () => {
  let stack = textmate.INITIAL;
  for (const line of ['M117 "open', "M118 {1 + "]) {
    stack = grammar.tokenizeLine(line, stack).ruleStack;
  }
  const next = grammar.tokenizeLine("G1 X1", stack).tokens;
  const g1 = next.find((t) => t.startIndex === 0);
  assert.ok(g1 && g1.scopes.includes("support.function.gcode.rrf-gcode"), JSON.stringify(next));
});
