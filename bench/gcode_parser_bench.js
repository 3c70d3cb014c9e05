// P3 comparison: parse a G-code file with the npm package gcode-parser@2.2.0 (cncjs), the way its README
// shows (parseStringSync keeps every parsed line, as rrflint keeps its parse). Installed by bench/run.sh into
// bench/node_modules. Usage: node bench/gcode_parser_bench.js FILE
'use strict';
const fs = require('fs');
const path = require('path');
const parser = require(path.join(__dirname, 'node_modules', 'gcode-parser'));

const text = fs.readFileSync(process.argv[2], 'utf8');
const results = parser.parseStringSync(text);
let words = 0;
for (const r of results) words += r.words.length;
process.stdout.write(`${results.length} lines, ${words} words\n`);
