#!/usr/bin/env node
// Unity .meta files of the UPM package: Unity ignores every asset of an installed (immutable)
// package that has no .meta, so each file and folder needs one, with a GUID unique and stable.
//   node .ci/unity-meta.mjs check  [dir] [--root-version package.json]  fails on any problem
//   node .ci/unity-meta.mjs create [dir]   writes the missing .meta files (new random GUIDs)
//   node .ci/unity-meta.mjs selftest       proves that check fails on broken trees
// Rules (Unity's asset database): dot-entries and folders ending in "~" are not imported and
// need no .meta, except that files under Samples~ are copied into Assets and do need them.
import fs from 'node:fs';
import path from 'node:path';
import os from 'node:os';
import crypto from 'node:crypto';

const hidden = (name) => name.startsWith('.');

// Yields the assets (files and folders) that need a .meta, relative to root.
function* assets(root, rel = '', importing = true) {
  for (const entry of fs.readdirSync(path.join(root, rel), { withFileTypes: true })) {
    if (hidden(entry.name) || entry.name.endsWith('.meta')) continue;
    const r = path.join(rel, entry.name);
    if (entry.isDirectory()) {
      if (entry.name.endsWith('~')) {
        if (entry.name === 'Samples~') yield* assets(root, r, true);
        continue;
      }
      if (importing) yield { rel: r, folder: true };
      yield* assets(root, r, importing);
    } else if (importing) {
      yield { rel: r, folder: false };
    }
  }
}

// Every .meta file below root (outside ignored folders), for orphan and GUID checks.
function* metas(root, rel = '') {
  for (const entry of fs.readdirSync(path.join(root, rel), { withFileTypes: true })) {
    if (hidden(entry.name)) continue;
    const r = path.join(rel, entry.name);
    if (entry.isDirectory()) {
      if (entry.name.endsWith('~') && entry.name !== 'Samples~') continue;
      yield* metas(root, r);
    } else if (entry.name.endsWith('.meta')) {
      yield r;
    }
  }
}

export function check(root, rootVersionFile) {
  const problems = [];
  let checked = 0;
  for (const a of assets(root)) {
    checked++;
    const meta = path.join(root, a.rel + '.meta');
    if (!fs.existsSync(meta)) problems.push(`missing ${a.rel}.meta`);
  }
  const guids = new Map();
  for (const m of metas(root)) {
    checked++;
    const asset = path.join(root, m.slice(0, -'.meta'.length));
    if (!fs.existsSync(asset)) problems.push(`orphan ${m} (its asset is missing)`);
    const text = fs.readFileSync(path.join(root, m), 'utf8');
    const g = /^guid: ([0-9a-f]{32})\s*$/m.exec(text);
    if (!/^fileFormatVersion: 2\s*$/m.test(text)) problems.push(`${m}: no "fileFormatVersion: 2"`);
    if (!g) {
      problems.push(`${m}: no "guid: <32 lowercase hex>" line`);
      continue;
    }
    if (guids.has(g[1])) problems.push(`duplicate guid ${g[1]} in ${m} and ${guids.get(g[1])}`);
    else guids.set(g[1], m);
    const isFolder = fs.existsSync(asset) && fs.statSync(asset).isDirectory();
    if (isFolder !== /^folderAsset: yes\s*$/m.test(text)) problems.push(`${m}: folderAsset does not match the asset`);
  }
  if (rootVersionFile) {
    checked++;
    const want = JSON.parse(fs.readFileSync(rootVersionFile, 'utf8')).version;
    const have = JSON.parse(fs.readFileSync(path.join(root, 'package.json'), 'utf8')).version;
    if (want !== have) problems.push(`package.json version ${have} != ${rootVersionFile} version ${want}`);
  }
  return { checked, problems };
}

function importerFor(rel, folder) {
  if (folder) return 'folderAsset: yes\nDefaultImporter:\n  externalObjects: {}\n';
  const ext = path.extname(rel).toLowerCase();
  if (ext === '.cs')
    return 'MonoImporter:\n  externalObjects: {}\n  serializedVersion: 2\n  defaultReferences: []\n' +
      '  executionOrder: 0\n  icon: {instanceID: 0}\n';
  if (ext === '.asmdef' || ext === '.asmref') return 'AssemblyDefinitionImporter:\n  externalObjects: {}\n';
  if (['.json', '.md', '.txt', ''].includes(ext)) return 'TextScriptImporter:\n  externalObjects: {}\n';
  return 'DefaultImporter:\n  externalObjects: {}\n';
}

export function create(root, quiet = false) {
  let n = 0;
  for (const a of assets(root)) {
    const meta = path.join(root, a.rel + '.meta');
    if (fs.existsSync(meta)) continue;
    const guid = crypto.randomUUID().replace(/-/g, '');
    fs.writeFileSync(meta, `fileFormatVersion: 2\nguid: ${guid}\n${importerFor(a.rel, a.folder)}` +
      '  userData: \n  assetBundleName: \n  assetBundleVariant: \n');
    if (!quiet) console.log(`created ${a.rel}.meta`);
    n++;
  }
  return n;
}

function selftest() {
  // A tiny package, then one breakage at a time: check must pass on the first, fail on the rest.
  const make = () => {
    const d = fs.mkdtempSync(path.join(os.tmpdir(), 'drape-meta-'));
    fs.mkdirSync(path.join(d, 'Runtime'));
    fs.mkdirSync(path.join(d, 'Documentation~'));
    fs.mkdirSync(path.join(d, 'Samples~/Flag'), { recursive: true });
    fs.writeFileSync(path.join(d, 'package.json'), '{"version":"1.2.3"}');
    fs.writeFileSync(path.join(d, 'Runtime/A.cs'), '');
    fs.writeFileSync(path.join(d, 'Documentation~/index.md'), '');
    fs.writeFileSync(path.join(d, 'Samples~/Flag/Flag.cs'), '');
    create(d, true);
    return d;
  };
  const rootVersion = path.join(fs.mkdtempSync(path.join(os.tmpdir(), 'drape-ver-')), 'package.json');
  fs.writeFileSync(rootVersion, '{"version":"1.2.3"}');
  const cases = {
    'complete tree': () => {},
    'missing meta': (d) => fs.rmSync(path.join(d, 'Runtime/A.cs.meta')),
    'missing meta in Samples~': (d) => fs.rmSync(path.join(d, 'Samples~/Flag/Flag.cs.meta')),
    'missing folder meta': (d) => fs.rmSync(path.join(d, 'Runtime.meta')),
    'orphan meta': (d) => fs.rmSync(path.join(d, 'Runtime/A.cs')),
    'duplicate guid': (d) => fs.copyFileSync(path.join(d, 'Runtime/A.cs.meta'), path.join(d, 'package.json.meta')),
    'version mismatch': (d) => fs.writeFileSync(path.join(d, 'package.json'), '{"version":"1.2.4"}'),
  };
  let failed = 0;
  for (const [name, breakIt] of Object.entries(cases)) {
    const d = make();
    breakIt(d);
    const { problems } = check(d, rootVersion);
    const ok = name === 'complete tree' ? problems.length === 0 : problems.length > 0;
    console.log(`${ok ? 'ok  ' : 'FAIL'} selftest: ${name}${problems.length ? ' -> ' + problems.join('; ') : ''}`);
    if (!ok) failed++;
    fs.rmSync(d, { recursive: true, force: true });
  }
  return failed;
}

const [cmd = 'check', dirArg = 'unity-package', ...rest] = process.argv.slice(2);
if (cmd === 'check') {
  const i = rest.indexOf('--root-version');
  const { checked, problems } = check(dirArg, i >= 0 ? rest[i + 1] : undefined);
  for (const p of problems) console.error(`unity-meta: ${p}`);
  console.log(`unity-meta: ${dirArg}: ${checked} entries checked, ${problems.length} problems`);
  process.exit(problems.length ? 1 : 0);
} else if (cmd === 'create') {
  console.log(`unity-meta: ${create(dirArg)} .meta files created`);
} else if (cmd === 'selftest') {
  process.exit(selftest() ? 1 : 0);
} else {
  console.error('usage: unity-meta.mjs check|create|selftest [dir] [--root-version file]');
  process.exit(2);
}
