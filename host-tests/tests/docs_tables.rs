//! The documentation's generated tables (`README.md`, `docs/accuracy.md`)
//! equal what `fixshade_host::report::docs_tables` computes from the
//! committed firmware measurements and the host's renders; `MAKE_DOCS=1`
//! rewrites them.

use fixshade_host::report::chips::{self, repo_root};
use fixshade_host::report::docs_tables::{block, find_block, replace_block, BLOCKS, REGENERATE};

#[test]
fn generated_docs_tables_are_current() {
    let root = repo_root();
    let ms = chips::load(&root.join(chips::DEFAULT_PATH)).unwrap();
    let write = std::env::var_os("MAKE_DOCS").is_some();
    let mut stale = Vec::new();
    for (file, name) in BLOCKS {
        let path = root.join(file);
        let text = std::fs::read_to_string(&path).unwrap();
        let want = block(name, &ms).unwrap();
        let have = find_block(&text, name)
            .unwrap_or_else(|| panic!("{file}: no block `{name}` (markers missing)"));
        if have != want {
            if write {
                let new = replace_block(&text, name, &want).unwrap();
                std::fs::write(&path, new).unwrap();
            } else {
                stale.push(format!(
                    "{file} `{name}`:\n--- committed{have}--- computed{want}"
                ));
            }
        }
    }
    assert!(
        stale.is_empty(),
        "generated tables differ (rewrite with `{REGENERATE}`):\n{}",
        stale.join("\n")
    );
}
