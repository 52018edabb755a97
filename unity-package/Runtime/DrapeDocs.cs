namespace Drape
{
    /// <summary>Where the package documentation is read online ([HelpURL] needs a constant URL).
    /// The same text ships in the package as Documentation~/index.md, which the Package Manager
    /// finds offline. PLACEHOLDER: the project has no public address yet; the reserved .invalid
    /// domain makes that obvious instead of sending users to a wrong site. Set it when published.</summary>
    public static class DrapeDocs
    {
        public const string Manual = "https://drape.invalid/unity-package/Documentation~/index.md";
    }
}
