// What the extension needs to start `rrflint server`, without VS Code: finding the binary and the settings the
// server is told about. Kept apart from extension.ts so that the tests run under plain node.
import * as fs from "fs";
import * as os from "os";
import * as path from "path";

/** The settings sent to the server, as rrflint's `firmware`, `select` and `ignore` options. */
export interface ServerSettings {
  firmware?: string;
  select?: string[];
  ignore?: string[];
}

/** The raw values of the `rrflint.*` settings that the server is told about. */
export interface RawSettings {
  firmware?: unknown;
  select?: unknown;
  ignore?: unknown;
}

function stringList(value: unknown): string[] | undefined {
  if (!Array.isArray(value)) {
    return undefined;
  }
  const items = value.filter((v): v is string => typeof v === "string" && v.trim() !== "").map((v) => v.trim());
  return items.length > 0 ? items : undefined;
}

/**
 * The server's settings from VS Code's: an empty firmware or an empty list is left out, so that `.rrflint.toml`
 * or rrflint's default applies (the server lets `.rrflint.toml` win anyway where both set a value).
 */
export function serverSettings(raw: RawSettings): ServerSettings {
  const out: ServerSettings = {};
  if (typeof raw.firmware === "string" && raw.firmware.trim() !== "") {
    out.firmware = raw.firmware.trim();
  }
  const select = stringList(raw.select);
  if (select) {
    out.select = select;
  }
  const ignore = stringList(raw.ignore);
  if (ignore) {
    out.ignore = ignore;
  }
  return out;
}

/** The parameters of `workspace/didChangeConfiguration`: `{"settings": {"rrflint": {...}}}`. */
export function didChangeConfigurationParams(settings: ServerSettings): { settings: { rrflint: ServerSettings } } {
  return { settings: { rrflint: settings } };
}

function isExecutableFile(file: string): boolean {
  try {
    if (!fs.statSync(file).isFile()) {
      return false;
    }
    fs.accessSync(file, process.platform === "win32" ? fs.constants.F_OK : fs.constants.X_OK);
    return true;
  } catch {
    return false;
  }
}

/** Where to look for the binary: the environment's PATH (on Windows, with PATHEXT) and HOME (for `~`). */
export type SearchEnv = { [name: string]: string | undefined };

/** The outcome of looking for the binary: its path, or a message that says what was looked for. */
export type Resolved = { ok: true; path: string } | { ok: false; message: string };

function onPath(name: string, env: SearchEnv): string | undefined {
  const exts = process.platform === "win32" ? ["", ...(env.PATHEXT ?? ".EXE;.CMD;.BAT").split(";")] : [""];
  for (const dir of (env.PATH ?? "").split(path.delimiter)) {
    if (dir === "") {
      continue;
    }
    for (const ext of exts) {
      const candidate = path.join(dir, name + ext);
      if (isExecutableFile(candidate)) {
        return candidate;
      }
    }
  }
  return undefined;
}

/**
 * Finds the rrflint binary: the `rrflint.path` setting when it is set (`~` is the home folder, a relative path is
 * taken from `base`, the first workspace folder), else `rrflint` on PATH.
 */
export function resolveBinary(setting: string, base: string | undefined, env: SearchEnv): Resolved {
  const wanted = setting.trim();
  if (wanted === "") {
    const found = onPath("rrflint", env);
    return found
      ? { ok: true, path: found }
      : {
          ok: false,
          message:
            "rrflint: the rrflint binary was not found on PATH. Install rrflint, or set rrflint.path to the binary.",
        };
  }
  let file = wanted;
  if (file === "~" || file.startsWith("~/")) {
    file = path.join(env.HOME ?? os.homedir(), file.slice(1));
  } else if (!path.isAbsolute(file) && base !== undefined) {
    file = path.resolve(base, file);
  }
  return isExecutableFile(file)
    ? { ok: true, path: file }
    : { ok: false, message: `rrflint: rrflint.path is set to '${wanted}', but ${file} is not an executable file.` };
}

/** The command line the extension starts: `<binary> server`, LSP over stdin/stdout. */
export function serverArgs(): string[] {
  return ["server"];
}
