// The absolute-mode inputs the module, the page and the native CLI share: the fixture
// (tests/cli/absolute_fixture.cpp) writes the page's example and the virtual bracket as DNGs and
// stimuli CSVs into a temporary folder, once per test file (removed after it), and the native CLI
// runs on them there.
import { after } from 'node:test';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { repoRoot } from './test_files.mjs';

export const nativeCli = path.join(repoRoot, 'build/native/core/tristim');
const fixtureExe = path.join(repoRoot, 'build/native/tests/absolute_fixture');

/// {dir(): the fixture's folder (written on first use), cli(cwd, args): the CLI's stdout}.
export function absoluteFixture(prefix) {
  let dir = null;
  after(() => { if (dir) fs.rmSync(dir, { recursive: true, force: true }); });
  return {
    dir() {
      if (dir) return dir;
      for (const f of [nativeCli, fixtureExe]) if (!fs.existsSync(f)) throw new Error(`${f} not found: build the native tree first (bash scripts/build.sh)`);
      dir = fs.mkdtempSync(path.join(os.tmpdir(), prefix));
      execFileSync(fixtureExe, [dir]);
      return dir;
    },
    cli: (cwd, args) => execFileSync(nativeCli, args, { cwd, stdio: ['ignore', 'pipe', 'pipe'] }).toString(),
  };
}
