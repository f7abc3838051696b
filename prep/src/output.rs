//! Writing the ground tool's outputs so that a failure never leaves half a file and no command
//! overwrites one of its own inputs.

use std::io::Write;
use std::path::{Path, PathBuf};

/// `path` with its folder resolved through the file system (symbolic links and `..`), so that
/// two names of one file compare equal; a path whose folder does not exist is returned as it is.
fn resolved(path: &Path) -> PathBuf {
    if let Ok(p) = path.canonicalize() {
        return p;
    }
    let parent = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    match (parent.canonicalize(), path.file_name()) {
        (Ok(dir), Some(name)) => dir.join(name),
        _ => path.to_path_buf(),
    }
}

/// Refuses an output path that names one of the command's inputs, or whose folder does not
/// exist (so that a long command fails before its work, not after it).
pub fn refuse_overwriting_inputs(output: &Path, inputs: &[&Path]) -> Result<(), String> {
    let folder = match output.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    if !folder.is_dir() {
        return Err(format!(
            "{}: the folder {} does not exist; create it first or choose another output path",
            output.display(),
            folder.display()
        ));
    }
    let out = resolved(output);
    for input in inputs {
        if resolved(input) == out {
            return Err(format!(
                "{}: the output would overwrite the input {}; choose another output path",
                output.display(),
                input.display()
            ));
        }
    }
    Ok(())
}

/// Writes `bytes` to `path` through a temporary file in the same folder, renamed over `path`
/// only once it is complete and flushed: readers see the old file or the whole new one, and a
/// failure leaves no partial output (the temporary file is removed).
pub fn write_atomically(path: &Path, bytes: &[u8]) -> Result<(), String> {
    let name = path
        .file_name()
        .ok_or_else(|| format!("{}: not a file name", path.display()))?;
    let mut tmp_name = std::ffi::OsString::from(".");
    tmp_name.push(name);
    tmp_name.push(format!(".skyroute-{}.tmp", std::process::id()));
    let tmp = path.with_file_name(tmp_name);
    let written = (|| -> std::io::Result<()> {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    written.map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        format!("{}: {e}", path.display())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn outputs_naming_an_input_or_in_a_missing_folder_are_refused() {
        let dir = std::env::temp_dir().join(format!("skyroute-output-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("sub")).unwrap();
        let input = dir.join("in.bin");
        std::fs::write(&input, b"x").unwrap();
        let other = dir.join("sub/../in.bin");
        assert!(refuse_overwriting_inputs(&other, &[&input]).is_err());
        assert!(refuse_overwriting_inputs(&dir.join("out.bin"), &[&input]).is_ok());
        // Not there yet, in an existing folder: compared by its resolved folder.
        assert!(refuse_overwriting_inputs(&dir.join("sub/new.bin"), &[&input]).is_ok());
        // In a folder that does not exist: refused, naming the folder.
        let e = refuse_overwriting_inputs(&dir.join("nowhere/new.bin"), &[&input]).unwrap_err();
        assert!(e.contains("nowhere does not exist"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_failed_write_leaves_nothing_behind() {
        let dir = std::env::temp_dir().join(format!("skyroute-atomic-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let target = dir.join("out.json");
        write_atomically(&target, b"whole").unwrap();
        assert_eq!(std::fs::read(&target).unwrap(), b"whole");
        // A folder where the file should go: the rename fails, the temporary file is removed.
        let blocked = dir.join("blocked");
        std::fs::create_dir_all(blocked.join("inner")).unwrap();
        assert!(write_atomically(&blocked, b"data").is_err());
        let left: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(left.len(), 2, "{left:?}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
